#pragma once
/// \file
/// \brief When a pass runs on several threads.
///
/// Every pass is a loop over particles that writes only particle i's own fields (or over cells,
/// each cell's by one thread), so it runs on OpenMP threads without locks and gives the same
/// bits for any thread count.  Starting the threads costs a few microseconds -- and far more
/// when another process holds a core, since each pass then waits for the slowest thread's next
/// time slice.  Below a few thousand particles a pass takes less time than that, so small
/// scenes run on one thread.

#include <cstddef>

namespace sph {

/// Loops over fewer particles than this run on one thread.
inline constexpr std::size_t parallel_threshold = 4096;

}  // namespace sph

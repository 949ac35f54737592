#pragma once
/// \file
/// \brief Where the neighbour search keeps its work: blocks of particles, each with the
/// candidates of its particles and the pairs they keep, one array per field.
///
/// NeighbourSearch (neighbour_search.hpp) splits the particles into blocks, one unit of work
/// for one thread at a time.  The types are plain arrays that only grow, so that a search
/// settles from step to step into buffers that are already large enough.

#include "sph/neighbours/cell_grid.hpp"
#include "sph/neighbours/neighbour_list.hpp"
#include "sph/neighbours/smoothing_length.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace sph {

namespace detail {

/// Candidates one array per field, so the refresh of their distances runs in SIMD registers.
/// The arrays only grow; `count` entries are in use.  What a particle keeps from step to step
/// is who its candidates are (index and image: StoredCandidates); their squared distances are
/// worked out afresh each step into a scratch array, and only a search's result carries them
/// (Candidates).
template <bool with_distance>
struct CandidateArrays {
  std::vector<std::uint32_t> index;
  std::vector<Image> image;
  std::vector<double> r2;  ///< (empty without distances)
  std::size_t count = 0;
  std::size_t size() const { return count; }
  void clear() { count = 0; }
  /// Room for `more` entries past the used ones.
  void reserve_more(std::size_t more) {
    if (count + more <= index.size()) return;
    const std::size_t n = std::max(count + more, 2 * index.size());
    index.resize(n);
    image.resize(n);
    if constexpr (with_distance) r2.resize(n);
  }
  /// Append entries first..last of `other` (who they are; distances only between two
  /// arrays that both have them).
  template <bool other_distance>
  void append(const CandidateArrays<other_distance>& other, std::size_t first, std::size_t last) {
    const std::size_t m = last - first;
    reserve_more(m);
    const auto from = static_cast<std::ptrdiff_t>(first), to = static_cast<std::ptrdiff_t>(count);
    std::copy_n(other.index.begin() + from, m, index.begin() + to);
    std::copy_n(other.image.begin() + from, m, image.begin() + to);
    if constexpr (with_distance && other_distance)
      std::copy_n(other.r2.begin() + from, m, r2.begin() + to);
    count += m;
  }
};
using Candidates = CandidateArrays<true>;
using StoredCandidates = CandidateArrays<false>;

/// The pairs (r_ij < 2h_i) of a range of particles: those of the k-th particle are entries
/// first[k] .. first[k] + count[k].  Written particle after particle; the array only grows,
/// `used` entries are in use.  (Their distances are not kept: writing and reading them back
/// cost more memory traffic than measuring the few that are needed again, find_reverse.)
struct KeptPairs {
  std::vector<std::size_t> first;
  std::vector<std::uint32_t> count;
  std::vector<Neighbour> pairs;
  std::size_t used = 0;
  void clear(std::size_t particles) {
    first.assign(particles, 0);
    count.assign(particles, 0);
    used = 0;
  }
  void reserve_more(std::size_t more) {
    if (used + more <= pairs.size()) return;
    pairs.resize(std::max(used + more, 2 * pairs.size()));
  }
};

/// A unit of work for one thread: a contiguous range of particles, its candidates and the pairs
/// it keeps.  Particle i's candidates are entries first_[i]..last_[i] of `candidates` (the
/// search holds first_ and last_); a particle searched again appends its new ones, and the
/// block is compacted when more than half its entries are stale.  The kept pairs (r_ij < 2h_i)
/// go to `kept`, particle after particle; one-sided pairs (r_ij < 2h_i but >= 2h_j) are
/// recorded in `reverse` so that j gets them too.
struct SearchBlock {
  std::size_t begin = 0, end = 0;
  StoredCandidates candidates, spare;  ///< (spare: the buffer a compaction copies into)
  std::size_t live = 0;                ///< entries some particle still refers to
  Candidates found;                    ///< the candidates of the particle being searched
  /// The distances of the particle being settled; when its pairs are checked for one-sided
  /// ones, its neighbours' (2h_j)^2 and then the distances.
  std::vector<double> r2;
  KeptPairs kept;
  std::vector<std::pair<std::uint32_t, Neighbour>> reverse;  ///< (j, entry for j)
  /// The candidates of particle i with room for their distances.
  CandidateSpan span(std::size_t first, std::size_t last) {
    if (r2.size() < last - first) r2.resize(2 * (last - first));
    return {candidates.index.data() + first, candidates.image.data() + first, r2.data(),
            last - first};
  }
};

}  // namespace detail

}  // namespace sph

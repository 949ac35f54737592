#pragma once
/// \file
/// \brief Keeping the candidates closer than a limit: the compaction that turns a particle's
/// candidates into its pairs, eight at a time with AVX-512 and in a plain loop elsewhere.

#include "sph/neighbours/cell_grid.hpp"
#include "sph/neighbours/neighbour_list.hpp"

#if defined(__AVX512F__)
#include <immintrin.h>
#endif

#include <algorithm>
#include <cstddef>
#include <cstdint>

namespace sph {

namespace detail {

/// Append to `out` the entries k < n of (index, image) with r2[k] < limit2, in order, and
/// return how many; `farthest2` gets the largest r2 among them (0 if none).  When `wrapped`
/// is given, each image is translated to image - own + wrapped[index]: from the frame of the
/// unwrapped positions, in which the search keeps candidates, to the frame of the stored ones
/// (own = wrapped[i] for the particle whose pairs these are; see NeighbourSearch::try_reuse).
/// `out` must have room for n entries: entries past the kept ones may be overwritten.
///
/// The plain loop writes every entry and advances the end past the kept ones only (no
/// branch to mispredict), but still moves one entry per iteration.  With AVX-512 the entries
/// go eight at a time: a mask of the kept ones, compressed to the front of the register and
/// stored whole (compressing in the register, not into memory: on some processors the store
/// form is microcoded and slow).  `portable` forces the plain loop, so tests can compare both.
template <bool portable = false>
inline std::size_t keep_closer(const std::uint32_t* index, const Image* image, const double* r2,
                               std::size_t n, double limit2, const Image* wrapped, Image own,
                               Neighbour* out, double& farthest2) {
  static_assert(sizeof(Neighbour) == 8, "a Neighbour must pack into one 64-bit lane");
  std::size_t end = 0, k = 0;
  double farthest = 0;
#if defined(__AVX512F__) && defined(__AVX512VL__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"  // (GCC 12, inside its own AVX-512 headers)
  if constexpr (!portable) {
    const __m512d limit = _mm512_set1_pd(limit2);
    const __m256i low = _mm256_set1_epi32(0x7f7f7f7f),
                  high = _mm256_set1_epi32(static_cast<int>(0x80808080u));
    const __m256i own_image = _mm256_set1_epi32(static_cast<int>(own));
    __m512d far = _mm512_setzero_pd();
    for (; k + 8 <= n; k += 8) {
      const __m512d d = _mm512_loadu_pd(r2 + k);
      const __mmask8 kept = _mm512_cmp_pd_mask(d, limit, _CMP_LT_OQ);
      const __m256i j = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(index + k));
      __m256i img = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(image + k));
      if (wrapped) {
        // subtract_images(img, own), then add_images(., wrapped[j]), eight lanes at once.
        const __m256i diff = _mm256_xor_si256(
            _mm256_sub_epi32(_mm256_or_si256(img, high), _mm256_and_si256(own_image, low)),
            _mm256_andnot_si256(_mm256_xor_si256(img, own_image), high));
        const __m256i w = _mm256_i32gather_epi32(reinterpret_cast<const int*>(wrapped), j, 4);
        img = _mm256_xor_si256(
            _mm256_add_epi32(_mm256_and_si256(diff, low), _mm256_and_si256(w, low)),
            _mm256_and_si256(_mm256_xor_si256(diff, w), high));
      }
      const __m512i pair = _mm512_or_si512(_mm512_cvtepu32_epi64(j),
                                           _mm512_slli_epi64(_mm512_cvtepu32_epi64(img), 32));
      _mm512_storeu_si512(out + end, _mm512_maskz_compress_epi64(kept, pair));
      far = _mm512_max_pd(far, _mm512_maskz_mov_pd(kept, d));
      end += static_cast<std::size_t>(__builtin_popcount(kept));
    }
    farthest = _mm512_reduce_max_pd(far);
  }
#pragma GCC diagnostic pop
#endif
  for (; k < n; ++k) {
    const Image img =
        wrapped ? add_images(subtract_images(image[k], own), wrapped[index[k]]) : image[k];
    out[end] = {index[k], img};
    farthest = std::max(farthest, r2[k] < limit2 ? r2[k] : 0.0);
    end += r2[k] < limit2;
  }
  farthest2 = farthest;
  return end;
}

}  // namespace detail

}  // namespace sph

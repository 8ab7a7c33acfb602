#include "schemes/fragments/block_writer.h"

#ifdef __x86_64__
#include <immintrin.h>
#endif

namespace sdb::fragments {
namespace {

void write_plain(const Lanes<kLanes>* position, const Lanes<kLanes>* normal, size_t begin, size_t n,
                 const float origin[3], Point3* const pos[kLanes], Point3* const nrm[kLanes], int lanes) {
  for (int l = 0; l < lanes; ++l)
    for (size_t i = begin; i < n; ++i) {
      const Lanes<kLanes>&p = position[i], &q = normal[i];
      pos[l][i] = {p.x[l] + origin[0], p.y[l] + origin[1], p.z[l] + origin[2]};
      nrm[l][i] = {q.x[l], q.y[l], q.z[l]};
    }
}

#ifdef __x86_64__
// One entry of eight lanes: x, y, z transposed into (x, y, z, 0) per lane and stored as 16 bytes
// at dst[l] + i. The fourth float lands on vertex i + 1's x, which the next entry writes: so every
// entry but a block's last goes this way.
__attribute__((target("avx"))) inline void store_entry(__m256 x, __m256 y, __m256 z, Point3* const dst[kLanes], size_t i) {
  const __m256 zero = _mm256_setzero_ps();
  const __m256 a = _mm256_unpacklo_ps(x, y), b = _mm256_unpackhi_ps(x, y);
  const __m256 c = _mm256_unpacklo_ps(z, zero), d = _mm256_unpackhi_ps(z, zero);
  const __m256 v[4] = {_mm256_shuffle_ps(a, c, _MM_SHUFFLE(1, 0, 1, 0)), _mm256_shuffle_ps(a, c, _MM_SHUFFLE(3, 2, 3, 2)),
                       _mm256_shuffle_ps(b, d, _MM_SHUFFLE(1, 0, 1, 0)), _mm256_shuffle_ps(b, d, _MM_SHUFFLE(3, 2, 3, 2))};
  for (int k = 0; k < 4; ++k) {
    _mm_storeu_ps(&dst[k][i][0], _mm256_castps256_ps128(v[k]));
    _mm_storeu_ps(&dst[k + 4][i][0], _mm256_extractf128_ps(v[k], 1));
  }
}

__attribute__((target("avx"))) void write_avx(const Lanes<kLanes>* position, const Lanes<kLanes>* normal, size_t n,
                                              const float origin[3], Point3* const pos[kLanes],
                                              Point3* const nrm[kLanes]) {
  const __m256 ox = _mm256_set1_ps(origin[0]), oy = _mm256_set1_ps(origin[1]), oz = _mm256_set1_ps(origin[2]);
  for (size_t i = 0; i + 1 < n; ++i) {
    const Lanes<kLanes>&p = position[i], &q = normal[i];
    store_entry(_mm256_add_ps(_mm256_loadu_ps(p.x), ox), _mm256_add_ps(_mm256_loadu_ps(p.y), oy),
                _mm256_add_ps(_mm256_loadu_ps(p.z), oz), pos, i);
    store_entry(_mm256_loadu_ps(q.x), _mm256_loadu_ps(q.y), _mm256_loadu_ps(q.z), nrm, i);
  }
  write_plain(position, normal, n - 1, n, origin, pos, nrm, kLanes);
}
#endif

}  // namespace

void write_blocks_in_order(const Lanes<kLanes>* position, const Lanes<kLanes>* normal, size_t n, const float origin[3],
                           Point3* const pos[kLanes], Point3* const nrm[kLanes], int lanes) {
  static_assert(kLanes == 8 && sizeof(Point3) == 12);
#ifdef __x86_64__
  static const bool avx = __builtin_cpu_supports("avx");
  if (avx && lanes == kLanes && n > 0) return write_avx(position, normal, n, origin, pos, nrm);
#endif
  write_plain(position, normal, 0, n, origin, pos, nrm, lanes);
}

}  // namespace sdb::fragments

#include "geometry/inside_edges.h"

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define POLYFLOE_X86_SIMD 1
#endif

namespace polyfloe::geometry {

namespace {

// One edge, q0 = poly[k - 1] to q1 = poly[k], as the vector variants do it lane by lane.
bool inside_edge(std::span<const Vec2> poly, const Vec2& origin, const Vec2& v, double margin, std::size_t k) {
  const std::size_t n = poly.size();
  const Vec2 q0 = poly[(k == 0) ? n - 1 : k - 1] - origin, q1 = poly[k] - origin;
  const Vec2 e = q1 - q0;
  return perp_right(e).dot(v - q0) < -margin * e.squaredNorm();
}

#if defined(POLYFLOE_X86_SIMD)

bool inside_sse2(std::span<const Vec2> poly, const Vec2& origin, const Vec2& v, double margin) {
  const std::size_t n = poly.size();
  const __m128d o = _mm_loadu_pd(origin.data());
  const __m128d vx = _mm_set1_pd(v.x()), vy = _mm_set1_pd(v.y());
  const __m128d neg_margin = _mm_set1_pd(-margin);
  __m128d pass = _mm_castsi128_pd(_mm_set1_epi32(-1));
  __m128d prev = _mm_sub_pd(_mm_loadu_pd(poly[n - 1].data()), o);  // (x, y) of poly[k - 1]
  std::size_t k = 0;
  for (; k + 2 <= n; k += 2) {
    const __m128d p0 = _mm_sub_pd(_mm_loadu_pd(poly[k].data()), o);
    const __m128d p1 = _mm_sub_pd(_mm_loadu_pd(poly[k + 1].data()), o);
    // Lanes: edges k and k + 1.
    const __m128d q0x = _mm_unpacklo_pd(prev, p0), q0y = _mm_unpackhi_pd(prev, p0);
    const __m128d q1x = _mm_unpacklo_pd(p0, p1), q1y = _mm_unpackhi_pd(p0, p1);
    const __m128d ex = _mm_sub_pd(q1x, q0x), ey = _mm_sub_pd(q1y, q0y);
    const __m128d dx = _mm_sub_pd(vx, q0x), dy = _mm_sub_pd(vy, q0y);
    const __m128d val = _mm_sub_pd(_mm_mul_pd(ey, dx), _mm_mul_pd(ex, dy));
    const __m128d len2 = _mm_add_pd(_mm_mul_pd(ex, ex), _mm_mul_pd(ey, ey));
    pass = _mm_and_pd(pass, _mm_cmplt_pd(val, _mm_mul_pd(neg_margin, len2)));
    prev = p1;
  }
  bool inside = _mm_movemask_pd(pass) == 3;
  if (k < n) inside = inside && inside_edge(poly, origin, v, margin, k);  // the last of an odd count
  return inside;
}

// Four edges at a time, in blocks of four from edge 0 (the last block starts at n - 4, so it may test a few edges
// again): each block's q1 is two unaligned loads, and so is its q0 but for the first block's, whose first vertex
// wraps around to poly[n - 1].
__attribute__((target("avx2"))) bool inside_avx2(std::span<const Vec2> poly, const Vec2& origin, const Vec2& v,
                                                 double margin) {
  const std::size_t n = poly.size();
  if (n < 4) return inside_sse2(poly, origin, v, margin);
  const double* p = poly.data()->data();  // x0, y0, x1, y1, ...
  const __m256d o = _mm256_setr_pd(origin.x(), origin.y(), origin.x(), origin.y());
  const __m256d vx = _mm256_set1_pd(v.x()), vy = _mm256_set1_pd(v.y());
  const __m256d neg_margin = _mm256_set1_pd(-margin);
  __m256d pass = _mm256_castsi256_pd(_mm256_set1_epi32(-1));
  for (std::size_t k = 0;; k += 4) {
    if (k + 4 > n) k = n - 4;
    const __m256d l0 = _mm256_sub_pd(_mm256_loadu_pd(p + 2 * k), o);      // poly[k], poly[k + 1]
    const __m256d l1 = _mm256_sub_pd(_mm256_loadu_pd(p + 2 * k + 4), o);  // poly[k + 2], poly[k + 3]
    const __m256d m0 = _mm256_sub_pd(                                     // poly[k - 1], poly[k]
        k == 0 ? _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(p + 2 * (n - 1))), _mm_loadu_pd(p), 1)
               : _mm256_loadu_pd(p + 2 * k - 2),
        o);
    const __m256d m1 = _mm256_sub_pd(_mm256_loadu_pd(p + 2 * k + 2), o);  // poly[k + 1], poly[k + 2]
    // Lanes: edges k, k + 2, k + 1, k + 3 (the order does not matter: every lane must pass).
    const __m256d q1x = _mm256_unpacklo_pd(l0, l1), q1y = _mm256_unpackhi_pd(l0, l1);
    const __m256d q0x = _mm256_unpacklo_pd(m0, m1), q0y = _mm256_unpackhi_pd(m0, m1);
    const __m256d ex = _mm256_sub_pd(q1x, q0x), ey = _mm256_sub_pd(q1y, q0y);
    const __m256d dx = _mm256_sub_pd(vx, q0x), dy = _mm256_sub_pd(vy, q0y);
    const __m256d val = _mm256_sub_pd(_mm256_mul_pd(ey, dx), _mm256_mul_pd(ex, dy));
    const __m256d len2 = _mm256_add_pd(_mm256_mul_pd(ex, ex), _mm256_mul_pd(ey, ey));
    pass = _mm256_and_pd(pass, _mm256_cmp_pd(val, _mm256_mul_pd(neg_margin, len2), _CMP_LT_OQ));
    if (k + 4 >= n) break;
  }
  return _mm256_movemask_pd(pass) == 15;
}

bool detect_avx2() {
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx2") != 0;
}

const bool kHasAvx2 = detect_avx2();

#endif  // POLYFLOE_X86_SIMD

}  // namespace

bool has_avx2() {
#if defined(POLYFLOE_X86_SIMD)
  return kHasAvx2;
#else
  return false;
#endif
}

bool inside_all_edges(std::span<const Vec2> poly, const Vec2& origin, const Vec2& v, double margin, EdgeSimd simd) {
  if (poly.empty()) return true;
#if defined(POLYFLOE_X86_SIMD)
  if (simd != EdgeSimd::sse2 && kHasAvx2) return inside_avx2(poly, origin, v, margin);
  return inside_sse2(poly, origin, v, margin);
#else
  (void)simd;
  bool inside = true;
  for (std::size_t k = 0; k < poly.size(); ++k) inside = inside && inside_edge(poly, origin, v, margin, k);
  return inside;
#endif
}

}  // namespace polyfloe::geometry

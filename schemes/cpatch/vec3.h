// Vec3f: the packed float triple every c-patch buffer holds (control points, coefficients), and
// its double twin for the reference evaluation in tests. Plain arithmetic, written out so that the
// order of floating-point operations is explicit: the watertightness argument (README.md,
// "Exact borders") depends on it.
#pragma once

#include <array>
#include <cmath>

namespace sdb::cpatch {

template <class T>
struct Vec3 {
  T x = 0, y = 0, z = 0;
};
using Vec3f = Vec3<float>;
using Vec3d = Vec3<double>;

template <class T>
inline Vec3<T> operator+(Vec3<T> a, Vec3<T> b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <class T>
inline Vec3<T> operator-(Vec3<T> a, Vec3<T> b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <class T>
inline Vec3<T> operator*(T s, Vec3<T> a) {
  return {s * a.x, s * a.y, s * a.z};
}
template <class T>
inline Vec3<T>& operator+=(Vec3<T>& a, Vec3<T> b) {
  return a = a + b;
}
template <class T>
inline Vec3<T> cross(Vec3<T> a, Vec3<T> b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <class T>
inline T dot(Vec3<T> a, Vec3<T> b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}

inline Vec3f to_vec3(const std::array<float, 3>& p) { return {p[0], p[1], p[2]}; }
inline std::array<float, 3> to_point3(Vec3f v) { return {v.x, v.y, v.z}; }
inline Vec3d to_double(Vec3f v) { return {v.x, v.y, v.z}; }

}  // namespace sdb::cpatch

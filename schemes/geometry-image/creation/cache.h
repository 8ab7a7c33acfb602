// ImageCache: fitted geometry images on disk, so that runs do not repeat the fit.
//
// One float32 OpenEXR file per image (three channels, the samples row-major, lossless zip),
// named gim-<key>-<n>.exr in $SUBDIVBENCH_CACHE, else ~/.cache/subdivbench. The key hashes the
// mesh's content and everything that shapes the result (creation version, fairness weight); the
// file's header repeats it, with the figures of the creation that made it (times, stretch, CG),
// the image's size and a checksum of its samples as written. A file is a cache, not a source of
// truth: what is read is verified (header key, size, every sample finite, the checksum) and a file
// that fails is refused with the reason, never used.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>

#include "schemes/geometry-image/image.h"

namespace sdb::gim {

struct CachedImage {
  GeometryImage image;
  std::map<std::string, double> figures;  // e.g. "fit_ms", as stored
  std::string path;
};

class ImageCache {
 public:
  explicit ImageCache(std::string directory = default_directory());
  static std::string default_directory();

  const std::string& directory() const { return directory_; }
  std::string path(uint64_t key, int n) const;
  // The image stored under (key, n), or nullopt: absent, or refused, when `refused` (if given)
  // says why ("... .exr: checksum mismatch (the samples changed since they were written)").
  std::optional<CachedImage> load(uint64_t key, int n, std::string* refused = nullptr) const;
  // Writes atomically (a temporary file renamed into place); returns the path, or an empty
  // string when the directory cannot be written (the cache is an optimisation, not a must).
  std::string store(uint64_t key, const GeometryImage& image, const std::map<std::string, double>& figures) const;

 private:
  std::string directory_;
};

}  // namespace sdb::gim

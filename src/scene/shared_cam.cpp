// camdyn — one Cam per cam spec (shared_cam.hpp).
#include "scene/shared_cam.hpp"

#include <sys/stat.h>

#include <deque>
#include <mutex>
#include <utility>

namespace camdyn {
namespace detail {
namespace {

constexpr std::size_t kKept = 8;

struct FileStamp {
  long long size = -1, mtime_ns = -1;
  bool operator==(const FileStamp& o) const { return size == o.size && mtime_ns == o.mtime_ns; }
};

FileStamp stamp_of(const CamSpec& spec) {
  FileStamp s;
  struct stat st {};
  if (spec.profile == CamProfileKind::Table && !spec.lift_table.empty() && ::stat(spec.lift_table.c_str(), &st) == 0) {
    s.size = static_cast<long long>(st.st_size);
    s.mtime_ns = static_cast<long long>(st.st_mtim.tv_sec) * 1000000000LL + st.st_mtim.tv_nsec;
  }
  return s;
}

struct Entry {
  CamSpec spec;
  FileStamp file;
  std::shared_ptr<const Cam> cam;
};

}  // namespace

std::shared_ptr<const Cam> shared_cam(const CamSpec& spec) {
  static std::mutex mu;
  static std::deque<Entry> kept;  // most recent first
  const FileStamp file = stamp_of(spec);
  {
    std::lock_guard<std::mutex> lock(mu);
    for (auto it = kept.begin(); it != kept.end(); ++it)
      if (it->file == file && it->spec == spec) {
        Entry e = std::move(*it);
        kept.erase(it);
        kept.push_front(std::move(e));
        return kept.front().cam;
      }
  }
  auto cam = std::make_shared<const Cam>(spec);  // outside the lock: may throw, may take a while
  std::lock_guard<std::mutex> lock(mu);
  kept.push_front(Entry{spec, file, cam});
  if (kept.size() > kKept) kept.pop_back();
  return cam;
}

}  // namespace detail
}  // namespace camdyn

// The memory libzip keeps for an opened archive, without any coatcontact code: RSS and heap in
// use (mallinfo2) before zip_open and after it, per entry of the central directory, for each
// open flag given. bench/afm_maps.sh runs it on the synthetic maps (issue 25's memory budget,
// THEORY.md section 15, "Many curves").
// Usage: zip_open_rss ARCHIVE [rdonly|none|checkcons]...   (default: rdonly)
// Prints "flags entries rss_kB heap_kB heap_bytes_per_entry" per flag.
#include <malloc.h>
#include <zip.h>

#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>

namespace {

long status_kb(const char* key) {
  std::ifstream in("/proc/self/status");
  std::string line;
  const std::size_t n = std::strlen(key);
  while (std::getline(in, line)) {
    if (line.compare(0, n, key) == 0) return std::stol(line.substr(n + 1));
  }
  return -1;
}

long heap_bytes() {
  const struct mallinfo2 m = mallinfo2();
  // uordblks: bytes in use from the main arena; hblkhd: bytes in mmap'ed blocks.
  return static_cast<long>(m.uordblks + m.hblkhd);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: zip_open_rss ARCHIVE [rdonly|none|checkcons]...\n");
    return 2;
  }
  int status = 0;
  for (int a = (argc > 2 ? 2 : 1); a < argc; ++a) {
    const std::string name = argc > 2 ? argv[a] : "rdonly";
    int flags = 0;
    if (name == "rdonly") flags = ZIP_RDONLY;
    else if (name == "checkcons") flags = ZIP_RDONLY | ZIP_CHECKCONS;
    else if (name != "none") {
      std::fprintf(stderr, "zip_open_rss: flag '%s' is not allowed; expected rdonly, none or checkcons\n", name.c_str());
      return 2;
    }
    const long rss0 = status_kb("VmRSS:");
    const long heap0 = heap_bytes();
    int code = 0;
    zip_t* archive = zip_open(argv[1], flags, &code);
    if (archive == nullptr) {
      std::fprintf(stderr, "zip_open_rss: %s: zip_open failed (code %d)\n", argv[1], code);
      return 1;
    }
    const zip_int64_t entries = zip_get_num_entries(archive, 0);
    // A name lookup builds nothing more in libzip 1.7 (its hash is filled at open); do one anyway.
    (void)zip_name_locate(archive, "header.properties", ZIP_FL_ENC_RAW);
    const long rss1 = status_kb("VmRSS:");
    const long heap1 = heap_bytes();
    std::printf("%s\t%lld\t%ld\t%ld\t%.1f\n", name.c_str(), static_cast<long long>(entries), rss1 - rss0,
                (heap1 - heap0) / 1024, entries > 0 ? static_cast<double>(heap1 - heap0) / static_cast<double>(entries) : 0.0);
    zip_discard(archive);
    if (entries <= 0) status = 1;
  }
  return status;
}

// Limits of the AFM readers (internal): what a file may declare before anything is allocated.
// Each is far above what the instruments write (the real files in data/afm/ in brackets), so
// only a corrupt or hostile file meets one; the message names the limit.
#pragma once
#include <cstddef>
#include <cstdint>

namespace coatcontact::afm::detail {

// A file read whole (Igor, AFM Workshop CSV/zip, NT-MDT text) [largest: 0.3 MB]; JPK archives
// are read entry by entry from their file and have no whole-file limit.
constexpr std::uint64_t kMaxWholeFileBytes = 256ull << 20;
// A JPK .properties entry (header, segment header, shared data) [largest: 127 KB].
constexpr std::uint64_t kMaxPropertiesBytes = 16ull << 20;
// Settings of one header once its references to the shared data are expanded [~2 000].
constexpr std::size_t kMaxSettings = 200000;
// Segments of one curve [3]; points of one segment [12 030] and of one curve.
constexpr int kMaxSegments = 1024;
constexpr std::size_t kMaxSegmentPoints = std::size_t{1} << 22;
constexpr std::size_t kMaxCurvePoints = std::size_t{1} << 23;
// An AFM Workshop CSV inside a zipped map [25 KB]; columns of its column line [6]; the sum of
// a zipped map's CSV entries.
constexpr std::uint64_t kMaxCsvEntryBytes = 64ull << 20;
constexpr std::size_t kMaxCsvColumns = 64;

}  // namespace coatcontact::afm::detail

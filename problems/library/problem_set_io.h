// The problem library on disk: one versioned, checksummed binary file per ProblemSet (".smcps"), with a matrix
// table so that a constant M is stored once. Byte-by-byte specification and the reasons for a format of our own
// rather than HDF5: problems/library/README.md.
//
// Reading never trusts the file: every size is checked against the bytes actually present before anything is
// allocated, the checksum is verified before any field is interpreted, and every defect is an InvalidInputError
// "problem set '<file>': <what> at byte <offset>: ..." naming the file, the field and the offset.
#pragma once

#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <memory>
#include <string>
#include <string_view>

#include "problems/library/problem_set.h"

namespace smcbench {

struct AviProblemSet;  // problems/avi_library/avi_library.h

// What a set holds, stored from version 4 on in the header's reserved field (0 in versions 1 to 3: box-MLCPs).
// Append-only, explicit values.
enum class ProblemSetKind : std::uint32_t {
  kBoxMlcp = 0,  // LibraryProblem (problem_set.h): ReadProblemSet
  kAvi = 1,      // AviLibraryProblem (problems/avi_library/avi_library.h): ReadAviProblemSet
};

// Format version of the sets of box-MLCPs this build writes. Version 2 added each problem's certified reference
// (certificate, condition, z*); version 1 files are still read, their problems with Certificate::kNone. Version 3
// (for captures of long runs) added the bounds table (l and u stored once, like M) and lets a problem continue the
// previous one's source, tags and metadata, storing only the entries that differ; a file that uses neither is
// laid out as version 2, and versions 1 and 2 are still read.
inline constexpr std::uint32_t kProblemSetFormatVersion = 3;
// Format version of the sets of AVIs this build writes. Version 4 added the set kind (the header's reserved field)
// and, in an AVI set, rectangular dense matrices and the AVI record; a set of box-MLCPs is still written as
// version 3, byte for byte as before (a writer writes the oldest version that can hold its set).
inline constexpr std::uint32_t kAviProblemSetFormatVersion = 4;
// The oldest and newest versions this build reads (every version in between is read).
inline constexpr std::uint32_t kOldestReadableProblemSetFormatVersion = 1;
inline constexpr std::uint32_t kNewestReadableProblemSetFormatVersion = 4;
// The customary file extension.
inline constexpr const char* kProblemSetExtension = ".smcps";
// Files larger than this (4 GiB) are refused before reading (10⁵ sparse rows with 10 entries each take ~15 MB).
inline constexpr std::uint64_t kMaxProblemSetFileBytes = std::uint64_t{1} << 32;
// Reading expands the matrix table (every problem owns its M): a small file whose problems share one large M
// could otherwise claim any amount of memory. Beyond this many bytes of matrix data (16 GiB) a read fails.
inline constexpr std::uint64_t kMaxExpandedMatrixBytes = std::uint64_t{1} << 34;
// The same for version 3's inherited text: a problem that continues the previous one's source, tags and metadata
// gets its own copy of them, so a file of small records could repeat a long text any number of times. Beyond this
// many inherited bytes (4 GiB) a read fails.
inline constexpr std::uint64_t kMaxInheritedTextBytes = std::uint64_t{1} << 32;

// Writes the whole set in version kProblemSetFormatVersion (set.Validate() first; identical matrices are stored
// once, compared bit by bit). Throws InvalidInputError if the set is invalid (duplicate or empty id, wrong solution
// size, non-finite solution, out-of-range enum value, a reference whose z* does not match its certificate, a NaN
// or negative condition) or the stream fails.
void WriteProblemSet(const ProblemSet& set, std::ostream& out);
// Same, to a file: written under a temporary name in the same folder and renamed at the end, so a failed write
// never leaves a half-written file under path.
void WriteProblemSetFile(const ProblemSet& set, const std::string& path);

// Reads a whole set. name_for_errors names the source in messages. The matrix table is expanded: every
// problem owns its copy of M in memory.
ProblemSet ReadProblemSet(std::istream& in, const std::string& name_for_errors);
ProblemSet ReadProblemSetFile(const std::string& path);
ProblemSet ReadProblemSetBytes(std::string_view bytes, const std::string& name_for_errors);

// What a file holds besides its problems (for listings; reads and checks the whole file like ReadProblemSet).
struct ProblemSetFileInfo {
  std::uint32_t version = 0;  // of the file (a version-1 file read by this build reports 1)
  ProblemSetKind kind = ProblemSetKind::kBoxMlcp;
  std::uint64_t bytes = 0;
  std::uint64_t matrices = 0;  // entries of the matrix table (distinct matrices)
  std::uint64_t problems = 0;
};
ProblemSet ReadProblemSetFile(const std::string& path, ProblemSetFileInfo* info);

// The kind of set a file holds, from its 16-byte header alone (magic, version and kind checked; nothing else is
// read), so that a command can pick the reader. InvalidInputError like the readers' for a bad header.
ProblemSetKind ReadProblemSetKind(const std::string& path);

// Sets of AVIs (version 4, set kind 1; specification in problems/library/README.md): the same framing, checksum,
// matrix table (M, H and E, identical matrices stored once, compared bit by bit) and reading discipline as the
// box sets. WriteAviProblemSet validates the set first (set.Validate(), plus what the reader refuses: a reference
// whose λ* is not the first n entries of its z*, multipliers of the wrong size, non-finite or out-of-range
// values, "infeasible" on a bounded P) and throws InvalidInputError naming the problem.
void WriteAviProblemSet(const AviProblemSet& set, std::ostream& out);
// Written under "<path>.partial" and renamed at the end, as WriteProblemSetFile.
void WriteAviProblemSetFile(const AviProblemSet& set, const std::string& path);
// Every AVI is built as an AffineVI (its own validation: no zero row, P not empty) and owns its matrices. A set of
// box-MLCPs is refused with a message naming its kind, as ReadProblemSet refuses a set of AVIs.
AviProblemSet ReadAviProblemSetBytes(std::string_view bytes, const std::string& name_for_errors);
AviProblemSet ReadAviProblemSetFile(const std::string& path, ProblemSetFileInfo* info = nullptr);

// The checksum of the format (FNV-1a 64) over bytes.
std::uint64_t ProblemSetChecksum(std::string_view bytes);
// Rewrites the last 8 bytes of a file image with the checksum of everything before them (what a valid file
// holds there). For tests and fuzz targets that edit a valid file and want the decoder, not the checksum, to
// judge the edit. No-op if bytes is shorter than 8.
void FixProblemSetChecksum(std::string* bytes);

// How a streaming writer keeps ids unique within its file.
//   kRemembered: it keeps every id written and refuses a repeat (memory grows with the number of problems).
//   kGuaranteedByCaller: it keeps none, for streams whose ids are distinct by construction (a capture of a run:
//     ProblemRecorder checks that its (step, Newton iteration) pairs strictly increase), so that a capture of any
//     length writes in constant memory. A repeated id written anyway makes the file unreadable (readers check).
enum class IdCheck { kRemembered, kGuaranteedByCaller };

struct ProblemSetWriterOptions {
  // Matrices kept in memory to recognize a repeated M (hash first, then a bit-by-bit comparison), most recently
  // used first, up to this many bytes of matrix data. The last matrix written is always kept, so consecutive
  // identical matrices (a linear stepper's constant M) are always stored once whatever the budget. (Bounds: the
  // last 16 distinct l, u are recognized.)
  std::size_t dedupe_cache_bytes = std::size_t{64} << 20;
  IdCheck id_check = IdCheck::kRemembered;
};

// Writes a set one problem at a time without holding the problems (captures of long runs). Add() validates like
// WriteProblemSet (ids must be unique within the file: the writer keeps the ids it has written, unless
// options.id_check says the caller guarantees it). Its memory is bounded (the caches above, one problem's text for
// the next one to continue). Close() writes
// the end record with the counts and the checksum; a file whose writer was never closed has no end record and
// every reader rejects it as truncated. The file variant writes to "<path>.partial" and renames it to path on
// Close(); destroying an unclosed file writer removes the partial file.
class ProblemSetWriter {
 public:
  ProblemSetWriter(const std::string& path, const std::string& set_name, const std::string& description,
                   ProblemSetWriterOptions options = {});
  // out must outlive the writer; name_for_errors names it in messages.
  ProblemSetWriter(std::ostream& out, const std::string& name_for_errors, const std::string& set_name,
                   const std::string& description, ProblemSetWriterOptions options = {});
  ~ProblemSetWriter();
  ProblemSetWriter(const ProblemSetWriter&) = delete;
  ProblemSetWriter& operator=(const ProblemSetWriter&) = delete;

  void Add(const LibraryProblem& problem);
  void Close();

  bool closed() const;
  std::uint64_t problems_written() const;
  std::uint64_t matrices_written() const;  // distinct matrices stored so far
  std::uint64_t bytes_written() const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace smcbench

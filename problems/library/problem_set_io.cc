// The ".smcps" problem-set format (specification: problems/library/README.md). Every integer and double is
// written and read byte by byte in little-endian order, whatever the host; nothing is ever dumped as a struct.
#include "problems/library/problem_set_io.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <istream>
#include <limits>
#include <list>
#include <map>
#include <optional>
#include <ostream>
#include <system_error>
#include <unordered_map>
#include <unordered_set>
#include <tuple>
#include <utility>
#include <vector>

#include "problems/avi_library/avi_library.h"
#include "solvers/core/number_text.h"

namespace smcbench {
namespace {

namespace fs = std::filesystem;

constexpr unsigned char kMagic[8] = {0x89, 'S', 'M', 'C', 'P', 'S', '\r', '\n'};
constexpr std::size_t kHeaderBytes = 16;        // magic, u32 version, u32 reserved (version 4: set kind)
constexpr std::size_t kRecordHeaderBytes = 9;   // u8 kind, u64 body length
constexpr std::uint64_t kEndBodyBytes = 24;     // u64 matrices, u64 problems, u64 checksum

// Kind 5 (the bounds table) exists from version 3 on, kind 6 from version 4 on and only in a set of AVIs.
enum RecordKind : std::uint8_t {
  kSetRecord = 1,
  kMatrixRecord = 2,
  kProblemRecord = 3,
  kEndRecord = 4,
  kBoundsRecord = 5,
  kAviRecord = 6
};
// Storage 2 (version 4) is the only one of a set of AVIs: H and E are not square, and an AffineVI is dense.
enum MatrixStorage : std::uint8_t { kDenseStorage = 0, kSparseStorage = 1, kDenseRectangularStorage = 2 };
// An AVI record's flags: bit 0, the AffineVI's name equals the id (not stored); bit 1, λ* is the only solution's λ.
enum AviFlags : std::uint8_t { kAviNameIsId = 1, kAviLambdaUnique = 2 };
constexpr std::uint8_t kKnownAviFlags = kAviNameIsId | kAviLambdaUnique;
// Bit 2: the BoxMLCP's name equals the id and is not stored (captures name their problems by id). Version 3:
// bit 3, l and u are an entry of the bounds table (u64 index) instead of 2n doubles; bit 4, source, tags and
// metadata continue the previous problem's (stored: an empty source, no tags, the metadata entries that differ).
enum ProblemFlags : std::uint8_t {
  kHasSeed = 1,
  kHasSolution = 2,
  kNameIsId = 4,
  kSharedBounds = 8,
  kInherits = 16
};
constexpr std::uint8_t kKnownFlagsV2 = kHasSeed | kHasSolution | kNameIsId;
constexpr std::uint8_t kKnownFlagsV3 = kKnownFlagsV2 | kSharedBounds | kInherits;
// The streaming writer recognizes repeated bounds among the last this many distinct ones (a capture has one).
constexpr std::size_t kBoundsCacheEntries = 16;

// Eigen's int indices bound every dimension and nnz.
constexpr std::uint64_t kMaxDimension = static_cast<std::uint64_t>(std::numeric_limits<int>::max());
constexpr std::uint64_t kMaxString = std::numeric_limits<std::uint32_t>::max();

const char* KindName(std::uint8_t kind) {
  switch (kind) {
    case kSetRecord: return "set record";
    case kMatrixRecord: return "matrix record";
    case kProblemRecord: return "problem record";
    case kEndRecord: return "end record";
    case kBoundsRecord: return "bounds record";
    case kAviRecord: return "AVI record";
  }
  return "record";
}

// FNV-1a 64 (Fowler–Noll–Vo): changing any single byte changes the hash (each step is a bijection of the state).
class Fnv1a64 {
 public:
  void Update(const void* data, std::size_t size) {
    const auto* p = static_cast<const unsigned char*>(data);
    std::uint64_t h = h_;
    for (std::size_t i = 0; i < size; ++i) {
      h ^= p[i];
      h *= 0x100000001b3ULL;
    }
    h_ = h;
  }
  std::uint64_t value() const { return h_; }

 private:
  std::uint64_t h_ = 0xcbf29ce484222325ULL;
};

std::uint64_t DoubleBits(double v) {
  std::uint64_t bits;
  std::memcpy(&bits, &v, sizeof bits);
  return bits;
}

double BitsDouble(std::uint64_t bits) {
  double v;
  std::memcpy(&v, &bits, sizeof v);
  return v;
}

void StoreLE(char* p, std::uint64_t v, int bytes) {
  for (int i = 0; i < bytes; ++i) p[i] = static_cast<char>((v >> (8 * i)) & 0xff);
}

std::uint64_t LoadLE(const char* p, int bytes) {
  std::uint64_t v = 0;
  for (int i = 0; i < bytes; ++i) v |= static_cast<std::uint64_t>(static_cast<unsigned char>(p[i])) << (8 * i);
  return v;
}

// Whether value is a Certificate this build knows. A switch without default, so that a new enumerator in
// verdict.h makes -Wswitch point here (the format must then say how it is stored).
bool KnownCertificate(std::uint8_t value) {
  switch (static_cast<Certificate>(value)) {
    case Certificate::kNone:
    case Certificate::kUnique:
    case Certificate::kDegenerate:
    case Certificate::kNonUnique:
    case Certificate::kNoneFound:
    case Certificate::kIsolated:
      return true;
  }
  return false;
}

// "0 none, 1 unique, ..., 5 isolated": the certificate values, for messages.
std::string KnownCertificates() {
  std::string s;
  for (int v = 0; v < 256 && KnownCertificate(static_cast<std::uint8_t>(v)); ++v) {
    s += (s.empty() ? "" : ", ") + std::to_string(v) + " " + std::string(ToString(static_cast<Certificate>(v)));
  }
  return s;
}

std::string Hex(std::uint64_t v) {
  static const char kDigits[] = "0123456789abcdef";
  std::string s = "0x";
  for (int shift = 60; shift >= 0; shift -= 4) s += kDigits[(v >> shift) & 15];
  return s;
}

// ------------------------------------------------------------------------------------------------------------
// Encoding

// Appends little-endian values to a byte buffer.
class Encoder {
 public:
  explicit Encoder(std::string* buffer) : buf_(buffer) {}
  void U8(std::uint8_t v) { buf_->push_back(static_cast<char>(v)); }
  void U32(std::uint32_t v) { StoreLE(Grow(4), v, 4); }
  void U64(std::uint64_t v) { StoreLE(Grow(8), v, 8); }
  void F64(double v) { StoreLE(Grow(8), DoubleBits(v), 8); }
  void F64s(const double* v, std::size_t count) {
    char* p = Grow(8 * count);
    for (std::size_t i = 0; i < count; ++i) StoreLE(p + 8 * i, DoubleBits(v[i]), 8);
  }
  void U32s(const int* v, std::size_t count) {
    char* p = Grow(4 * count);
    for (std::size_t i = 0; i < count; ++i) StoreLE(p + 4 * i, static_cast<std::uint32_t>(v[i]), 4);
  }
  void Str(const std::string& s) {
    U32(static_cast<std::uint32_t>(s.size()));
    buf_->append(s);
  }

 private:
  char* Grow(std::size_t n) {
    const std::size_t old = buf_->size();
    buf_->resize(old + n);
    return buf_->data() + old;
  }
  std::string* buf_;
};

// A matrix as stored in a BoxMLCP, or a copy kept by the writer's cache.
struct MatrixView {
  bool sparse = false;
  const DenseMatrix* dense = nullptr;
  const SparseMatrix* sp = nullptr;

  static MatrixView Of(const BoxMLCP& p) {
    MatrixView v;
    v.sparse = p.is_sparse();
    if (v.sparse) {
      v.sp = &p.sparse_matrix();
    } else {
      v.dense = &p.dense_matrix();
    }
    return v;
  }
  std::size_t bytes() const {
    if (!sparse) return static_cast<std::size_t>(dense->size()) * 8;
    return static_cast<std::size_t>(sp->outerSize() + 1) * 4 + static_cast<std::size_t>(sp->nonZeros()) * 12;
  }
};

std::uint64_t MatrixHash(const MatrixView& m) {
  Fnv1a64 h;
  const unsigned char storage = m.sparse ? kSparseStorage : kDenseStorage;
  h.Update(&storage, 1);
  if (!m.sparse) {
    const Eigen::Index n = m.dense->rows();
    h.Update(&n, sizeof n);
    h.Update(m.dense->data(), static_cast<std::size_t>(m.dense->size()) * sizeof(double));
  } else {
    const SparseMatrix& s = *m.sp;
    const Eigen::Index n = s.rows(), nnz = s.nonZeros();
    h.Update(&n, sizeof n);
    h.Update(&nnz, sizeof nnz);
    h.Update(s.outerIndexPtr(), static_cast<std::size_t>(s.outerSize() + 1) * sizeof(int));
    h.Update(s.innerIndexPtr(), static_cast<std::size_t>(nnz) * sizeof(int));
    h.Update(s.valuePtr(), static_cast<std::size_t>(nnz) * sizeof(double));
  }
  return h.value();
}

// Bit-by-bit equality (so −0.0 ≠ 0.0, and two matrices equal here encode to identical bytes).
bool SameBits(const MatrixView& a, const MatrixView& b) {
  if (a.sparse != b.sparse) return false;
  if (!a.sparse) {
    return a.dense->rows() == b.dense->rows() && a.dense->cols() == b.dense->cols() &&
           std::memcmp(a.dense->data(), b.dense->data(), static_cast<std::size_t>(a.dense->size()) * 8) == 0;
  }
  const SparseMatrix &x = *a.sp, &y = *b.sp;
  if (x.rows() != y.rows() || x.cols() != y.cols() || x.nonZeros() != y.nonZeros()) return false;
  const auto nnz = static_cast<std::size_t>(x.nonZeros());
  return std::memcmp(x.outerIndexPtr(), y.outerIndexPtr(), static_cast<std::size_t>(x.outerSize() + 1) * 4) == 0 &&
         std::memcmp(x.innerIndexPtr(), y.innerIndexPtr(), nnz * 4) == 0 &&
         std::memcmp(x.valuePtr(), y.valuePtr(), nnz * 8) == 0;
}

// An owned copy of a matrix (the writer's dedupe cache).
struct MatrixCopy {
  bool sparse = false;
  DenseMatrix dense;
  SparseMatrix sp;

  explicit MatrixCopy(const MatrixView& v) : sparse(v.sparse) {
    if (sparse) {
      sp = *v.sp;
      sp.makeCompressed();
    } else {
      dense = *v.dense;
    }
  }
  MatrixView view() const {
    MatrixView v;
    v.sparse = sparse;
    v.dense = &dense;
    v.sp = &sp;
    return v;
  }
};

// l and u of a problem, hashed and compared bit by bit (the bounds table's key).
std::uint64_t BoundsHash(const Vector& l, const Vector& u) {
  Fnv1a64 h;
  const Eigen::Index n = l.size();
  h.Update(&n, sizeof n);
  h.Update(l.data(), static_cast<std::size_t>(n) * sizeof(double));
  h.Update(u.data(), static_cast<std::size_t>(n) * sizeof(double));
  return h.value();
}

bool SameBounds(const Vector& l1, const Vector& u1, const Vector& l2, const Vector& u2) {
  const auto bytes = static_cast<std::size_t>(l1.size()) * sizeof(double);
  return l1.size() == l2.size() && std::memcmp(l1.data(), l2.data(), bytes) == 0 &&
         std::memcmp(u1.data(), u2.data(), bytes) == 0;
}

// Bounds seen by a writer: the first problem with them stores them inline (a file whose bounds never repeat is
// laid out as in version 2); the second writes them to the bounds table, and it and every later one refer to it.
struct BoundsEntry {
  std::uint64_t hash = 0;
  Vector l, u;
  std::optional<std::uint64_t> index;  // the bounds-table entry, once written
};

// What a problem may inherit from the previous one (version 3, flag bit 4).
struct InheritedFields {
  std::string source;
  std::vector<std::string> tags;
  std::map<std::string, std::string> metadata;
};

// Whether p can continue previous (same source and tags, every key of previous in p) and saves bytes doing so.
bool CanInherit(const LibraryProblem& p, const InheritedFields& previous) {
  if (previous.source.empty() && previous.tags.empty() && previous.metadata.empty()) return false;
  if (p.source != previous.source || p.tags != previous.tags) return false;
  for (const auto& [key, value] : previous.metadata) {
    if (!p.metadata.count(key)) return false;
  }
  return true;
}

}  // namespace

// ------------------------------------------------------------------------------------------------------------
// Writer

struct ProblemSetWriter::Impl {
  std::ostream* out = nullptr;
  std::unique_ptr<std::ofstream> file;
  std::string path, partial_path;  // file variant only
  std::string name;                // for messages
  ProblemSetWriterOptions options;
  Fnv1a64 checksum;
  std::uint64_t bytes = 0, matrices = 0, problems = 0, bounds_records = 0;
  bool closed = false;
  std::unordered_set<std::string> ids;  // IdCheck::kRemembered only
  std::string body, record_header;
  // Bounds seen so far, most recently used first: the streaming writer keeps kBoundsCacheEntries, the whole-set
  // writer all of them (bounds_by_hash indexes the list then).
  std::list<BoundsEntry> bounds;
  std::size_t bounds_cache_entries = kBoundsCacheEntries;
  std::unordered_map<std::uint64_t, std::vector<std::list<BoundsEntry>::iterator>> bounds_by_hash;
  bool index_bounds = false;
  std::optional<InheritedFields> previous;  // of the last problem written
  // The header's version and set kind: a set of box-MLCPs keeps version 3 (its bytes as before version 4).
  std::uint32_t version = kProblemSetFormatVersion;
  ProblemSetKind kind = ProblemSetKind::kBoxMlcp;

  struct CacheEntry {
    std::uint64_t hash;
    std::uint64_t index;
    MatrixCopy matrix;
    std::size_t bytes;
  };
  std::list<CacheEntry> cache;  // most recently used first
  std::size_t cache_bytes = 0;

  [[noreturn]] void Fail(const std::string& what) const {
    throw InvalidInputError("problem set '" + name + "': " + what);
  }

  void Emit(const char* data, std::size_t size, bool hashed) {
    if (hashed) checksum.Update(data, size);
    out->write(data, static_cast<std::streamsize>(size));
    if (!*out) {
      Fail("write failed at byte " + std::to_string(bytes) +
           (file ? ": " + std::generic_category().message(errno) : std::string()));
    }
    bytes += size;
  }

  void WriteRecord(std::uint8_t kind, const std::string& data) {
    record_header.resize(kRecordHeaderBytes);
    record_header[0] = static_cast<char>(kind);
    StoreLE(record_header.data() + 1, data.size(), 8);
    Emit(record_header.data(), record_header.size(), true);
    Emit(data.data(), data.size(), true);
  }

  void Begin(const std::string& set_name, const std::string& description) {
    if (set_name.size() > kMaxString || description.size() > kMaxString) Fail("set name or description too long");
    char header[kHeaderBytes];
    std::memcpy(header, kMagic, sizeof kMagic);
    StoreLE(header + 8, version, 4);
    StoreLE(header + 12, static_cast<std::uint32_t>(kind), 4);
    Emit(header, sizeof header, true);
    body.clear();
    Encoder e(&body);
    e.Str(set_name);
    e.Str(description);
    WriteRecord(kSetRecord, body);
  }

  // Writes M as the next entry of the matrix table; returns its index.
  std::uint64_t WriteMatrix(const MatrixView& m, const std::string& id) {
    body.clear();
    Encoder e(&body);
    if (!m.sparse) {
      const DenseMatrix& M = *m.dense;
      body.reserve(9 + static_cast<std::size_t>(M.size()) * 8);
      e.U8(kDenseStorage);
      e.U64(static_cast<std::uint64_t>(M.rows()));
      e.F64s(M.data(), static_cast<std::size_t>(M.size()));  // Eigen's default storage is column-major
    } else {
      const SparseMatrix& S = *m.sp;
      if (!S.isCompressed()) Fail("problem '" + id + "': sparse M is not compressed");
      const int n = static_cast<int>(S.outerSize());
      const int* outer = S.outerIndexPtr();
      const int* inner = S.innerIndexPtr();
      // The reader insists on strictly increasing row indices per column (no duplicates, Eigen's invariant).
      for (int j = 0; j < n; ++j) {
        for (int k = outer[j] + 1; k < outer[j + 1]; ++k) {
          if (inner[k] <= inner[k - 1]) {
            Fail("problem '" + id + "': sparse M has unsorted or repeated row indices in column " +
                 std::to_string(j));
          }
        }
      }
      const auto nnz = static_cast<std::size_t>(S.nonZeros());
      body.reserve(17 + static_cast<std::size_t>(n + 1) * 4 + nnz * 12);
      e.U8(kSparseStorage);
      e.U64(static_cast<std::uint64_t>(n));
      e.U64(nnz);
      e.U32s(outer, static_cast<std::size_t>(n) + 1);
      e.U32s(inner, nnz);
      e.F64s(S.valuePtr(), nnz);
    }
    WriteRecord(kMatrixRecord, body);
    return matrices++;
  }

  // Checks what BoxMLCP does not guarantee, so that nothing is written that the reader would refuse.
  void CheckProblem(const LibraryProblem& p) {
    if (closed) Fail("Add() after Close()");
    if (p.id.empty()) Fail("problem #" + std::to_string(problems) + " has an empty id");
    const std::string who = "problem '" + p.id + "'";
    if (p.size() < 1) Fail(who + ": n = 0 (a problem needs at least one unknown)");
    if (p.solution.size() != 0 && p.solution.size() != p.size()) {
      Fail(who + ": solution has size " + std::to_string(p.solution.size()) + " but n = " + std::to_string(p.size()));
    }
    for (Eigen::Index i = 0; i < p.solution.size(); ++i) {
      if (!std::isfinite(p.solution[i])) Fail(who + ": solution[" + std::to_string(i) + "] is not finite");
    }
    for (Tristate t : {p.matrix.symmetric, p.matrix.positive_definite, p.matrix.p_matrix}) {
      if (static_cast<std::uint8_t>(t) > 2) {
        Fail(who + ": a matrix tag has the invalid value " + std::to_string(static_cast<int>(t)));
      }
    }
    if (static_cast<std::uint8_t>(p.expected) > 2) {
      Fail(who + ": expected outcome has the invalid value " + std::to_string(static_cast<int>(p.expected)));
    }
    CheckReference(p, who);
    bool long_string = p.id.size() > kMaxString || p.source.size() > kMaxString ||
                       p.problem.name().size() > kMaxString || p.tags.size() > kMaxString ||
                       p.metadata.size() > kMaxString;
    for (const auto& t : p.tags) long_string = long_string || t.size() > kMaxString;
    for (const auto& [k, v] : p.metadata) long_string = long_string || k.size() > kMaxString || v.size() > kMaxString;
    if (long_string) Fail(who + ": a string or list is longer than 2^32 - 1");
    if (options.id_check == IdCheck::kRemembered && ids.count(p.id)) Fail("duplicate id '" + p.id + "'");
  }

  // The reference as the reader will see it: a known certificate, a condition that is not NaN or negative, z* of
  // size n and finite exactly when the certificate verified one.
  void CheckReference(const LibraryProblem& p, const std::string& who) {
    const ReferenceSolution& r = p.reference;
    const auto certificate = static_cast<std::uint8_t>(r.certificate);
    if (!KnownCertificate(certificate)) {
      Fail(who + ": reference certificate has the invalid value " + std::to_string(certificate));
    }
    if (std::isnan(r.condition) || r.condition < 0.0) {
      Fail(who + ": reference condition is " + NumberText(r.condition) + " (must be >= 0, +inf allowed)");
    }
    if (r.verified()) {
      if (r.z.size() != p.size()) {
        Fail(who + ": reference certificate '" + std::string(ToString(r.certificate)) + "' with z* of size " +
             std::to_string(r.z.size()) + " but n = " + std::to_string(p.size()));
      }
      for (Eigen::Index i = 0; i < r.z.size(); ++i) {
        if (!std::isfinite(r.z[i])) Fail(who + ": reference z[" + std::to_string(i) + "] is not finite");
      }
    } else if (r.z.size() != 0) {
      Fail(who + ": reference certificate '" + std::string(ToString(r.certificate)) +
           "' verified no solution but z* is set (size " + std::to_string(r.z.size()) + ")");
    }
  }

  // The bounds-table entry for l, u if they were seen before (written to the table now if the first problem
  // with them stored them inline); nullopt the first time (the caller stores them inline).
  std::optional<std::uint64_t> BoundsIndex(const Vector& l, const Vector& u) {
    const std::uint64_t hash = BoundsHash(l, u);
    std::list<BoundsEntry>::iterator found = bounds.end();
    if (index_bounds) {
      const auto it = bounds_by_hash.find(hash);
      if (it != bounds_by_hash.end()) {
        for (const auto& entry : it->second) {
          if (SameBounds(entry->l, entry->u, l, u)) found = entry;
        }
      }
    } else {
      for (auto it = bounds.begin(); it != bounds.end() && found == bounds.end(); ++it) {
        if (it->hash == hash && SameBounds(it->l, it->u, l, u)) found = it;
      }
    }
    if (found == bounds.end()) {
      bounds.push_front(BoundsEntry{hash, l, u, std::nullopt});
      if (index_bounds) {
        bounds_by_hash[hash].push_back(bounds.begin());
      } else if (bounds.size() > bounds_cache_entries) {
        bounds.pop_back();
      }
      return std::nullopt;
    }
    if (!index_bounds) bounds.splice(bounds.begin(), bounds, found);
    if (!found->index) found->index = WriteBounds(l, u);
    return found->index;
  }

  // Writes l, u as the next entry of the bounds table; returns its index.
  std::uint64_t WriteBounds(const Vector& l, const Vector& u) {
    const auto n = static_cast<std::size_t>(l.size());
    body.clear();
    body.reserve(8 + 16 * n);
    Encoder e(&body);
    e.U64(n);
    e.F64s(l.data(), n);
    e.F64s(u.data(), n);
    WriteRecord(kBoundsRecord, body);
    return bounds_records++;
  }

  void WriteProblem(const LibraryProblem& p, std::uint64_t matrix_index) {
    const BoxMLCP& b = p.problem;
    const auto n = static_cast<std::size_t>(b.size());
    const std::optional<std::uint64_t> bounds_index = BoundsIndex(b.l(), b.u());
    const bool inherits = previous && CanInherit(p, *previous);
    body.clear();
    body.reserve(64 + p.id.size() + p.source.size() + n * 32);
    Encoder e(&body);
    e.Str(p.id);
    e.Str(inherits ? std::string() : p.source);
    const bool name_is_id = b.name() == p.id;
    e.U8(static_cast<std::uint8_t>((p.seed ? kHasSeed : 0) | (p.solution.size() ? kHasSolution : 0) |
                                   (name_is_id ? kNameIsId : 0) | (bounds_index ? kSharedBounds : 0) |
                                   (inherits ? kInherits : 0)));
    if (!name_is_id) e.Str(b.name());
    e.U64(matrix_index);
    e.U64(n);
    e.F64s(b.q().data(), n);
    if (bounds_index) {
      e.U64(*bounds_index);
    } else {
      e.F64s(b.l().data(), n);
      e.F64s(b.u().data(), n);
    }
    e.U8(static_cast<std::uint8_t>(p.matrix.symmetric));
    e.U8(static_cast<std::uint8_t>(p.matrix.positive_definite));
    e.U8(static_cast<std::uint8_t>(p.matrix.p_matrix));
    e.U8(static_cast<std::uint8_t>(p.expected));
    if (p.seed) e.U64(*p.seed);
    if (p.solution.size()) e.F64s(p.solution.data(), n);
    if (inherits) {
      // No tags (the previous problem's); the metadata entries that are new or differ from the previous ones.
      e.U32(0);
      const auto differs = [&](const std::string& key, const std::string& value) {
        const auto it = previous->metadata.find(key);
        return it == previous->metadata.end() || it->second != value;
      };
      std::uint32_t changed = 0;
      for (const auto& [k, v] : p.metadata) changed += differs(k, v) ? 1 : 0;
      e.U32(changed);
      for (const auto& [k, v] : p.metadata) {
        if (differs(k, v)) e.Str(k), e.Str(v);
      }
    } else {
      e.U32(static_cast<std::uint32_t>(p.tags.size()));
      for (const auto& t : p.tags) e.Str(t);
      e.U32(static_cast<std::uint32_t>(p.metadata.size()));
      for (const auto& [k, v] : p.metadata) {
        e.Str(k);
        e.Str(v);
      }
    }
    // Version 2: the certified reference.
    e.U8(static_cast<std::uint8_t>(p.reference.certificate));
    e.F64(p.reference.condition);
    if (p.reference.verified()) e.F64s(p.reference.z.data(), n);
    WriteRecord(kProblemRecord, body);
    if (options.id_check == IdCheck::kRemembered) ids.insert(p.id);
    if (!previous) previous.emplace();
    previous->source = p.source;
    previous->tags = p.tags;
    previous->metadata = p.metadata;
    ++problems;
  }

  // The streaming writer's lookup: the cache of recent matrices, hash first, then bits.
  std::uint64_t MatrixIndex(const BoxMLCP& problem, const std::string& id) {
    const MatrixView view = MatrixView::Of(problem);
    const std::uint64_t hash = MatrixHash(view);
    for (auto it = cache.begin(); it != cache.end(); ++it) {
      if (it->hash == hash && SameBits(it->matrix.view(), view)) {
        cache.splice(cache.begin(), cache, it);
        return it->index;
      }
    }
    const std::uint64_t index = WriteMatrix(view, id);
    const std::size_t size = view.bytes();
    cache.push_front(CacheEntry{hash, index, MatrixCopy(view), size});
    cache_bytes += size;
    while (cache.size() > 1 && cache_bytes > options.dedupe_cache_bytes) {
      cache_bytes -= cache.back().bytes;
      cache.pop_back();
    }
    return index;
  }

  void Finish() {
    if (closed) return;
    char end[kEndBodyBytes];
    StoreLE(end, matrices, 8);
    StoreLE(end + 8, problems, 8);
    record_header.resize(kRecordHeaderBytes);
    record_header[0] = static_cast<char>(kEndRecord);
    StoreLE(record_header.data() + 1, kEndBodyBytes, 8);
    Emit(record_header.data(), record_header.size(), true);
    Emit(end, 16, true);
    StoreLE(end + 16, checksum.value(), 8);
    Emit(end + 16, 8, false);
    out->flush();
    if (!*out) Fail("flush failed at byte " + std::to_string(bytes));
    if (file) {
      file->close();
      if (!*file) Fail("closing '" + partial_path + "' failed");
      std::error_code ec;
      fs::rename(partial_path, path, ec);
      if (ec) Fail("renaming '" + partial_path + "' to '" + path + "' failed: " + ec.message());
    }
    closed = true;
  }
};

ProblemSetWriter::ProblemSetWriter(const std::string& path, const std::string& set_name,
                                   const std::string& description, ProblemSetWriterOptions options)
    : impl_(std::make_unique<Impl>()) {
  Impl& w = *impl_;
  w.name = path;
  w.path = path;
  w.partial_path = path + ".partial";
  w.options = options;
  w.file = std::make_unique<std::ofstream>(w.partial_path, std::ios::binary | std::ios::trunc);
  if (!*w.file) {
    w.Fail("cannot open '" + w.partial_path + "' for writing: " + std::generic_category().message(errno));
  }
  w.out = w.file.get();
  try {
    w.Begin(set_name, description);
  } catch (...) {
    w.file.reset();
    std::error_code ec;
    fs::remove(w.partial_path, ec);
    throw;
  }
}

ProblemSetWriter::ProblemSetWriter(std::ostream& out, const std::string& name_for_errors,
                                   const std::string& set_name, const std::string& description,
                                   ProblemSetWriterOptions options)
    : impl_(std::make_unique<Impl>()) {
  impl_->out = &out;
  impl_->name = name_for_errors;
  impl_->options = options;
  impl_->Begin(set_name, description);
}

ProblemSetWriter::~ProblemSetWriter() {
  if (impl_ && impl_->file && !impl_->closed) {
    impl_->file.reset();
    std::error_code ec;
    fs::remove(impl_->partial_path, ec);
  }
}

void ProblemSetWriter::Add(const LibraryProblem& problem) {
  impl_->CheckProblem(problem);
  impl_->WriteProblem(problem, impl_->MatrixIndex(problem.problem, problem.id));
}

void ProblemSetWriter::Close() { impl_->Finish(); }
bool ProblemSetWriter::closed() const { return impl_->closed; }
std::uint64_t ProblemSetWriter::problems_written() const { return impl_->problems; }
std::uint64_t ProblemSetWriter::matrices_written() const { return impl_->matrices; }
std::uint64_t ProblemSetWriter::bytes_written() const { return impl_->bytes; }

void WriteProblemSet(const ProblemSet& set, std::ostream& out) {
  set.Validate();
  ProblemSetWriter::Impl w;
  w.out = &out;
  w.name = set.name;
  w.index_bounds = true;  // every distinct l, u is remembered (the set is in memory anyway)
  w.Begin(set.name, set.description);
  // The whole set is at hand: every repeated matrix is found (hash, then bits), without copying any.
  std::unordered_map<std::uint64_t, std::vector<std::pair<std::uint64_t, MatrixView>>> table;
  for (const LibraryProblem& p : set.problems) {
    w.CheckProblem(p);
    const MatrixView view = MatrixView::Of(p.problem);
    auto& bucket = table[MatrixHash(view)];
    std::uint64_t index = std::numeric_limits<std::uint64_t>::max();
    for (const auto& [i, other] : bucket) {
      if (SameBits(other, view)) {
        index = i;
        break;
      }
    }
    if (index == std::numeric_limits<std::uint64_t>::max()) {
      index = w.WriteMatrix(view, p.id);
      bucket.emplace_back(index, view);
    }
    w.WriteProblem(p, index);
  }
  w.Finish();
}

namespace {

// Writes a set to path through write(set, stream): under a temporary name in the same folder, renamed at the end,
// so a failed write never leaves a half-written file under path (the partial file is removed).
template <typename Set, typename Write>
void WriteSetFileAtomically(const Set& set, const std::string& path, Write write) {
  const std::string partial = path + ".partial";
  try {
    std::ofstream out(partial, std::ios::binary | std::ios::trunc);
    if (!out) {
      throw InvalidInputError("problem set '" + path + "': cannot open '" + partial +
                              "' for writing: " + std::generic_category().message(errno));
    }
    write(set, out);
    out.close();
    if (!out) throw InvalidInputError("problem set '" + path + "': closing '" + partial + "' failed");
    std::error_code ec;
    fs::rename(partial, path, ec);
    if (ec) throw InvalidInputError("problem set '" + path + "': renaming '" + partial + "' failed: " + ec.message());
  } catch (...) {
    std::error_code ec;
    fs::remove(partial, ec);
    throw;
  }
}

}  // namespace

void WriteProblemSetFile(const ProblemSet& set, const std::string& path) {
  WriteSetFileAtomically(set, path, [](const ProblemSet& s, std::ostream& out) { WriteProblemSet(s, out); });
}

// ------------------------------------------------------------------------------------------------------------
// Sets of AVIs (version 4, set kind 1)

namespace {

std::uint64_t DenseHash(const DenseMatrix& A) {
  Fnv1a64 h;
  const Eigen::Index rows = A.rows(), cols = A.cols();
  h.Update(&rows, sizeof rows);
  h.Update(&cols, sizeof cols);
  h.Update(A.data(), static_cast<std::size_t>(A.size()) * sizeof(double));
  return h.value();
}

// Empty ones are equal by their sizes: their data() may be null, which memcmp must not see.
bool SameDenseBits(const DenseMatrix& a, const DenseMatrix& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() &&
         (a.size() == 0 || std::memcmp(a.data(), b.data(), static_cast<std::size_t>(a.size()) * sizeof(double)) == 0);
}

bool SameVectorBits(const Vector& a, const Vector& b) {
  return a.size() == b.size() &&
         (a.size() == 0 || std::memcmp(a.data(), b.data(), static_cast<std::size_t>(a.size()) * sizeof(double)) == 0);
}

// The matrix table of an AVI set: every distinct M, H and E written once (hash, then bits).
class DenseTableWriter {
 public:
  explicit DenseTableWriter(ProblemSetWriter::Impl* w) : w_(w) {}

  std::uint64_t Index(const DenseMatrix& A) {
    auto& bucket = table_[DenseHash(A)];
    for (const auto& [index, other] : bucket) {
      if (SameDenseBits(*other, A)) return index;
    }
    std::string& body = w_->body;
    body.clear();
    body.reserve(17 + static_cast<std::size_t>(A.size()) * 8);
    Encoder e(&body);
    e.U8(kDenseRectangularStorage);
    e.U64(static_cast<std::uint64_t>(A.rows()));
    e.U64(static_cast<std::uint64_t>(A.cols()));
    e.F64s(A.data(), static_cast<std::size_t>(A.size()));  // column-major, Eigen's default
    w_->WriteRecord(kMatrixRecord, body);
    const std::uint64_t index = w_->matrices++;
    bucket.emplace_back(index, &A);
    return index;
  }

 private:
  ProblemSetWriter::Impl* w_;
  std::unordered_map<std::uint64_t, std::vector<std::pair<std::uint64_t, const DenseMatrix*>>> table_;
};

// What AviProblemSet::Validate does not check and the reader refuses.
void CheckAviForWriting(const AviLibraryProblem& p, const std::string& set_name) {
  const std::string who = "problem set '" + QuoteForMessage(set_name) + "': AVI '" + QuoteForMessage(p.id) + "'";
  const auto fail = [&](const std::string& what) { throw InvalidInputError(who + ": " + what); };
  const AffineVI& avi = *p.problem;
  const auto n = static_cast<std::uint64_t>(avi.size()), m = static_cast<std::uint64_t>(avi.inequality_count()),
             equalities = static_cast<std::uint64_t>(avi.equality_count());
  if (n + m + equalities > static_cast<std::uint64_t>(std::numeric_limits<int>::max())) {
    fail("n + m + p is above 2^31 - 1");
  }
  bool long_string = p.id.size() > kMaxString || p.source.size() > kMaxString || avi.name().size() > kMaxString ||
                     p.tags.size() > kMaxString || p.metadata.size() > kMaxString;
  for (const auto& t : p.tags) long_string = long_string || t.size() > kMaxString;
  for (const auto& [k, v] : p.metadata) long_string = long_string || k.size() > kMaxString || v.size() > kMaxString;
  if (long_string) fail("a string or list is longer than 2^32 - 1");
  if (static_cast<std::uint8_t>(p.expected) > 2) {
    fail("expected outcome has the invalid value " + std::to_string(static_cast<int>(p.expected)));
  }
  if (p.expected == ExpectedOutcome::kInfeasible && avi.boundedness() == PolytopeBoundedness::kBounded) {
    fail("expected infeasible, but P is bounded, so the AVI has a solution (Hartman-Stampacchia)");
  }
  const AviReference& r = p.reference;
  if (static_cast<std::uint8_t>(r.strictly_monotone) > 2) {
    fail("reference strictly_monotone has the invalid value " +
         std::to_string(static_cast<int>(r.strictly_monotone)));
  }
  const auto certificate = static_cast<std::uint8_t>(r.reduced.certificate);
  if (!KnownCertificate(certificate)) {
    fail("reference certificate has the invalid value " + std::to_string(certificate));
  }
  if (std::isnan(r.reduced.condition) || r.reduced.condition < 0.0) {
    fail("reference condition is " + NumberText(r.reduced.condition) + " (must be >= 0, +inf allowed)");
  }
  if (r.verified()) {
    const Vector& z = r.reduced.z;
    if (static_cast<std::uint64_t>(z.size()) != n + m + equalities || !z.allFinite()) {
      fail("reference z* has " + std::to_string(z.size()) + " entries (n + m + p = " +
           std::to_string(n + m + equalities) + " expected) or one that is not finite");
    }
    // λ* is stored once, as the head of z* (SplitReducedSolution), so it must be exactly that.
    if (!SameVectorBits(r.solution.lambda, z.head(static_cast<Eigen::Index>(n)))) {
      fail("reference lambda is not the first n entries of z* bit for bit");
    }
    if (static_cast<std::uint64_t>(r.solution.mu.size()) != m || !r.solution.mu.allFinite() ||
        static_cast<std::uint64_t>(r.solution.nu.size()) != equalities || !r.solution.nu.allFinite()) {
      fail("reference mu must have m and nu p finite entries");
    }
  } else {
    if (r.reduced.z.size() != 0 || r.solution.lambda.size() != 0 || r.solution.mu.size() != 0 ||
        r.solution.nu.size() != 0) {
      fail("reference certificate '" + std::string(ToString(r.reduced.certificate)) +
           "' verified no solution but z* or lambda, mu, nu is set");
    }
    if (r.lambda_unique) fail("reference lambda_unique without a verified solution");
  }
}

}  // namespace

void WriteAviProblemSet(const AviProblemSet& set, std::ostream& out) {
  set.Validate();
  for (const AviLibraryProblem& p : set.problems) CheckAviForWriting(p, set.name);
  ProblemSetWriter::Impl w;
  w.out = &out;
  w.name = set.name;
  w.version = kAviProblemSetFormatVersion;
  w.kind = ProblemSetKind::kAvi;
  w.Begin(set.name, set.description);
  DenseTableWriter table(&w);
  for (const AviLibraryProblem& p : set.problems) {
    const AffineVI& avi = *p.problem;
    const auto n = static_cast<std::size_t>(avi.size()), m = static_cast<std::size_t>(avi.inequality_count()),
               equalities = static_cast<std::size_t>(avi.equality_count());
    // The matrices first: a record may refer only to matrices written before it.
    const std::uint64_t M_index = table.Index(avi.M());
    const std::uint64_t H_index = m > 0 ? table.Index(avi.H()) : 0;
    const std::uint64_t E_index = equalities > 0 ? table.Index(avi.E()) : 0;
    std::string& body = w.body;
    body.clear();
    body.reserve(128 + p.id.size() + p.source.size() + (3 * n + 3 * m + 3 * equalities) * 8);
    Encoder e(&body);
    e.Str(p.id);
    e.Str(p.source);
    const bool name_is_id = avi.name() == p.id;
    e.U8(static_cast<std::uint8_t>((name_is_id ? kAviNameIsId : 0) |
                                   (p.reference.lambda_unique ? kAviLambdaUnique : 0)));
    if (!name_is_id) e.Str(avi.name());
    e.U64(n);
    e.U64(M_index);
    e.F64s(avi.q().data(), n);
    e.U64(m);
    if (m > 0) e.U64(H_index);
    e.F64s(avi.K().data(), m);
    e.U64(equalities);
    if (equalities > 0) e.U64(E_index);
    e.F64s(avi.f().data(), equalities);
    e.U8(static_cast<std::uint8_t>(p.expected));
    e.U32(static_cast<std::uint32_t>(p.tags.size()));
    for (const auto& t : p.tags) e.Str(t);
    e.U32(static_cast<std::uint32_t>(p.metadata.size()));
    for (const auto& [k, v] : p.metadata) {
      e.Str(k);
      e.Str(v);
    }
    const AviReference& r = p.reference;
    e.U8(static_cast<std::uint8_t>(r.strictly_monotone));
    e.U8(static_cast<std::uint8_t>(r.reduced.certificate));
    e.F64(r.reduced.condition);
    if (r.verified()) {
      e.F64s(r.reduced.z.data(), n + m + equalities);
      e.F64s(r.solution.mu.data(), m);
      e.F64s(r.solution.nu.data(), equalities);
    }
    w.WriteRecord(kAviRecord, body);
    ++w.problems;
  }
  w.Finish();
}

void WriteAviProblemSetFile(const AviProblemSet& set, const std::string& path) {
  WriteSetFileAtomically(set, path, [](const AviProblemSet& s, std::ostream& out) { WriteAviProblemSet(s, out); });
}

// ------------------------------------------------------------------------------------------------------------
// Reading

namespace {

// The decoded matrix table.
struct TableMatrix {
  bool sparse = false;
  DenseMatrix dense;
  SparseMatrix sp;
  Eigen::Index n = 0;
};

// Bounds-checked little-endian reads of one record body [pos, end) of the file image. Every failure names the
// file, the record (where), the field and the byte offset.
class Decoder {
 public:
  Decoder(std::string_view data, std::size_t begin, std::size_t end, const std::string& file, std::string where)
      : data_(data), pos_(begin), end_(end), file_(file), where_(std::move(where)) {}

  [[noreturn]] void FailAt(std::size_t offset, const std::string& field, const std::string& what) const {
    throw InvalidInputError("problem set '" + file_ + "': " + where_ + (field.empty() ? "" : " " + field) +
                            " at byte " + std::to_string(offset) + ": " + what);
  }
  [[noreturn]] void Fail(const std::string& field, const std::string& what) const { FailAt(pos_, field, what); }

  std::size_t pos() const { return pos_; }
  std::size_t remaining() const { return end_ - pos_; }
  void set_where(std::string where) { where_ = std::move(where); }
  const std::string& where() const { return where_; }

  // Before allocating count elements of size bytes: are they in the record at all?
  void Need(std::uint64_t count, std::size_t size, const std::string& field) const {
    if (count > remaining() / size) {
      Fail(field, "declares " + std::to_string(count) + " value(s) of " + std::to_string(size) +
                      " byte(s) but only " + std::to_string(remaining()) +
                      " byte(s) remain in the record (corrupt size field)");
    }
  }

  std::uint64_t Unsigned(int bytes, const char* field) {
    Need(1, static_cast<std::size_t>(bytes), field);
    const std::uint64_t v = LoadLE(data_.data() + pos_, bytes);
    pos_ += static_cast<std::size_t>(bytes);
    return v;
  }
  std::uint8_t U8(const char* field) { return static_cast<std::uint8_t>(Unsigned(1, field)); }
  std::uint32_t U32(const char* field) { return static_cast<std::uint32_t>(Unsigned(4, field)); }
  std::uint64_t U64(const char* field) { return Unsigned(8, field); }

  std::string Str(const std::string& field) {
    const std::uint32_t length = U32((field + " length").c_str());
    Need(length, 1, field);
    std::string s(data_.data() + pos_, length);
    pos_ += length;
    return s;
  }

  // count doubles (already checked with Need); check(i, v) may reject a value, given its offset.
  template <typename Check>
  void F64s(double* out, std::size_t count, Check&& check) {
    for (std::size_t i = 0; i < count; ++i) {
      out[i] = BitsDouble(LoadLE(data_.data() + pos_, 8));
      check(i, out[i], pos_);
      pos_ += 8;
    }
  }

  void ExpectEnd() const {
    if (pos_ != end_) Fail("", std::to_string(end_ - pos_) + " unexpected trailing byte(s) inside the record");
  }

 private:
  std::string_view data_;
  std::size_t pos_, end_;
  const std::string& file_;
  std::string where_;
};

std::string Index(const char* field, std::size_t i) { return std::string(field) + "[" + std::to_string(i) + "]"; }

TableMatrix DecodeMatrix(Decoder& d) {
  TableMatrix m;
  const std::size_t storage_at = d.pos();
  const std::uint8_t storage = d.U8("storage");
  if (storage != kDenseStorage && storage != kSparseStorage) {
    d.FailAt(storage_at, "storage", "unknown storage " + std::to_string(storage) +
                                            " (0 dense, 1 sparse CSC; 2, dense rows x cols, only in a set of AVIs)");
  }
  const std::size_t n_at = d.pos();
  const std::uint64_t n = d.U64("n");
  if (n < 1 || n > kMaxDimension) {
    d.FailAt(n_at, "n", "n = " + std::to_string(n) + " is outside [1, " + std::to_string(kMaxDimension) + "]");
  }
  const auto nn = static_cast<Eigen::Index>(n);
  m.n = nn;
  if (storage == kDenseStorage) {
    m.sparse = false;
    // n·n values, checked without forming n·n (it may overflow).
    if (n > d.remaining() / 8 / n) {
      d.Fail("M", "a dense " + std::to_string(n) + "x" + std::to_string(n) + " matrix needs more than the " +
                      std::to_string(d.remaining()) + " byte(s) left in the record (corrupt size field)");
    }
    m.dense.resize(nn, nn);
    d.F64s(m.dense.data(), static_cast<std::size_t>(n * n), [&](std::size_t i, double v, std::size_t at) {
      if (!std::isfinite(v)) {
        d.FailAt(at, "M(" + std::to_string(i % n) + "," + std::to_string(i / n) + ")",
                 std::isnan(v) ? "is NaN" : "is infinite");
      }
    });
  } else {
    m.sparse = true;
    const std::size_t nnz_at = d.pos();
    const std::uint64_t nnz = d.U64("nnz");
    if (nnz > kMaxDimension) {
      d.FailAt(nnz_at, "nnz", "nnz = " + std::to_string(nnz) + " exceeds " + std::to_string(kMaxDimension));
    }
    d.Need(n + 1, 4, "column pointers");
    std::vector<int> outer(static_cast<std::size_t>(n) + 1);
    for (std::uint64_t j = 0; j <= n; ++j) {
      const std::size_t at = d.pos();
      const std::uint32_t v = d.U32("column pointer");
      const std::uint32_t previous = j == 0 ? 0 : static_cast<std::uint32_t>(outer[j - 1]);
      if ((j == 0 && v != 0) || v < previous || v > nnz) {
        d.FailAt(at, Index("column pointer", j),
                 "value " + std::to_string(v) + " breaks 0 = p[0] <= p[1] <= ... <= p[n] = nnz = " +
                     std::to_string(nnz));
      }
      outer[j] = static_cast<int>(v);
    }
    if (static_cast<std::uint64_t>(outer[n]) != nnz) {
      d.Fail(Index("column pointer", n), "ends at " + std::to_string(outer[n]) + " but nnz = " + std::to_string(nnz));
    }
    d.Need(nnz, 12, "row indices and values");
    m.sp.resize(nn, nn);
    m.sp.resizeNonZeros(static_cast<Eigen::Index>(nnz));
    std::copy(outer.begin(), outer.end(), m.sp.outerIndexPtr());
    int* inner = m.sp.innerIndexPtr();
    for (std::uint64_t j = 0; j < n; ++j) {
      for (int k = outer[j]; k < outer[j + 1]; ++k) {
        const std::size_t at = d.pos();
        const std::uint32_t row = d.U32("row index");
        if (row >= n || (k > outer[j] && row <= static_cast<std::uint32_t>(inner[k - 1]))) {
          d.FailAt(at, Index("row index", static_cast<std::size_t>(k)),
                   "row " + std::to_string(row) + " in column " + std::to_string(j) +
                       (row >= n ? " is >= n = " + std::to_string(n) : " is not above the previous row index"));
        }
        inner[k] = static_cast<int>(row);
      }
    }
    d.F64s(m.sp.valuePtr(), static_cast<std::size_t>(nnz), [&](std::size_t k, double v, std::size_t at) {
      if (!std::isfinite(v)) d.FailAt(at, Index("value", k), std::isnan(v) ? "is NaN" : "is infinite");
    });
  }
  d.ExpectEnd();
  return m;
}

// The bounds table (version 3): l and u of n rows; NaN never, and every row oriented as BoxMLCP requires
// (l ≤ u, l < +∞, u > −∞), checked here so that the error names the record.
struct TableBounds {
  Vector l, u;
};

TableBounds DecodeBounds(Decoder& d) {
  const std::size_t n_at = d.pos();
  const std::uint64_t n = d.U64("n");
  if (n < 1 || n > kMaxDimension) {
    d.FailAt(n_at, "n", "n = " + std::to_string(n) + " is outside [1, " + std::to_string(kMaxDimension) + "]");
  }
  d.Need(n, 16, "l, u");
  TableBounds b;
  b.l.resize(static_cast<Eigen::Index>(n));
  b.u.resize(static_cast<Eigen::Index>(n));
  const auto count = static_cast<std::size_t>(n);
  d.F64s(b.l.data(), count, [&](std::size_t i, double v, std::size_t at) {
    if (std::isnan(v)) d.FailAt(at, Index("l", i), "is NaN");
    if (v == kInf) d.FailAt(at, Index("l", i), "is +inf");
  });
  d.F64s(b.u.data(), count, [&](std::size_t i, double v, std::size_t at) {
    if (std::isnan(v)) d.FailAt(at, Index("u", i), "is NaN");
    if (v == -kInf) d.FailAt(at, Index("u", i), "is -inf");
    if (b.l[static_cast<Eigen::Index>(i)] > v) {
      d.FailAt(at, Index("u", i), "u = " + NumberText(v) + " < l = " + NumberText(b.l[static_cast<Eigen::Index>(i)]));
    }
  });
  d.ExpectEnd();
  return b;
}

Tristate DecodeTristate(Decoder& d, const char* field) {
  const std::size_t at = d.pos();
  const std::uint8_t v = d.U8(field);
  if (v > 2) d.FailAt(at, field, "value " + std::to_string(v) + " is not 0 (unknown), 1 (no) or 2 (yes)");
  return static_cast<Tristate>(v);
}

// Version 2's reference fields: certificate, condition, z* when the certificate verified one.
ReferenceSolution DecodeReference(Decoder& d, std::uint64_t n, Eigen::Index size) {
  ReferenceSolution r;
  const std::size_t certificate_at = d.pos();
  const std::uint8_t certificate = d.U8("certificate");
  if (!KnownCertificate(certificate)) {
    d.FailAt(certificate_at, "certificate",
             "value " + std::to_string(certificate) + " is not a known certificate (" + KnownCertificates() + ")");
  }
  r.certificate = static_cast<Certificate>(certificate);
  const std::size_t condition_at = d.pos();
  r.condition = BitsDouble(d.U64("condition"));
  if (std::isnan(r.condition) || r.condition < 0.0) {
    d.FailAt(condition_at, "condition", std::isnan(r.condition) ? "is NaN" : "is negative");
  }
  if (r.verified()) {
    d.Need(n, 8, "reference z");
    r.z.resize(size);
    d.F64s(r.z.data(), static_cast<std::size_t>(n), [&](std::size_t i, double v, std::size_t at) {
      if (!std::isfinite(v)) d.FailAt(at, Index("reference z", i), std::isnan(v) ? "is NaN" : "is infinite");
    });
  }
  return r;
}

// previous: the problem decoded before this one (null for the first), which a version-3 problem may continue
// (flag bit 4); *inherited_bytes grows by the bytes of source, tags and metadata it takes from it.
LibraryProblem DecodeProblem(Decoder& d, const std::vector<TableMatrix>& table,
                             const std::vector<TableBounds>& bounds_table, std::uint32_t version,
                             const LibraryProblem* previous, std::uint64_t* inherited_bytes) {
  std::string id = d.Str("id");
  d.set_where(d.where() + " ('" + QuoteForMessage(id) + "')");
  const std::size_t source_at = d.pos();
  std::string source = d.Str("source");
  const std::size_t flags_at = d.pos();
  const std::uint8_t flags = d.U8("flags");
  const std::uint8_t known = version >= 3 ? kKnownFlagsV3 : kKnownFlagsV2;
  if (flags & ~known) d.FailAt(flags_at, "flags", "unknown flag bits " + Hex(flags & ~known));
  const bool inherits = (flags & kInherits) != 0;
  if (inherits && previous == nullptr) {
    d.FailAt(flags_at, "flags",
             "bit 4 (continue the previous problem's source, tags and metadata) on the first problem");
  }
  if (inherits && !source.empty()) {
    d.FailAt(source_at, "source", "must be empty when flag bit 4 (continue the previous problem) is set");
  }
  std::string name = (flags & kNameIsId) ? id : d.Str("name");
  const std::size_t index_at = d.pos();
  const std::uint64_t index = d.U64("matrix index");
  if (index >= table.size()) {
    d.FailAt(index_at, "matrix index", "refers to matrix " + std::to_string(index) + " but only " +
                                           std::to_string(table.size()) + " precede this problem");
  }
  const TableMatrix& M = table[static_cast<std::size_t>(index)];
  const std::size_t n_at = d.pos();
  const std::uint64_t n = d.U64("n");
  if (n != static_cast<std::uint64_t>(M.n)) {
    d.FailAt(n_at, "n", "n = " + std::to_string(n) + " but matrix " + std::to_string(index) + " is " +
                            std::to_string(M.n) + "x" + std::to_string(M.n));
  }
  const auto count = static_cast<std::size_t>(n);
  const bool shared_bounds = (flags & kSharedBounds) != 0;
  d.Need(n, shared_bounds ? 8 : 24, shared_bounds ? "q" : "q, l, u");
  Vector q(M.n), l(M.n), u(M.n);
  d.F64s(q.data(), count, [&](std::size_t i, double v, std::size_t at) {
    if (!std::isfinite(v)) d.FailAt(at, Index("q", i), std::isnan(v) ? "is NaN" : "is infinite");
  });
  if (shared_bounds) {
    const std::size_t bounds_at = d.pos();
    const std::uint64_t b = d.U64("bounds index");
    if (b >= bounds_table.size()) {
      d.FailAt(bounds_at, "bounds index", "refers to bounds " + std::to_string(b) + " but only " +
                                              std::to_string(bounds_table.size()) + " precede this problem");
    }
    const TableBounds& entry = bounds_table[static_cast<std::size_t>(b)];
    if (entry.l.size() != M.n) {
      d.FailAt(bounds_at, "bounds index", "bounds " + std::to_string(b) + " have " + std::to_string(entry.l.size()) +
                                              " rows but n = " + std::to_string(n));
    }
    l = entry.l;
    u = entry.u;
  } else {
    // Bounds may be ±∞; NaN never. Orientation (l < +∞, u > −∞, l ≤ u) is BoxMLCP's check, below.
    d.F64s(l.data(), count, [&](std::size_t i, double v, std::size_t at) {
      if (std::isnan(v)) d.FailAt(at, Index("l", i), "is NaN");
    });
    d.F64s(u.data(), count, [&](std::size_t i, double v, std::size_t at) {
      if (std::isnan(v)) d.FailAt(at, Index("u", i), "is NaN");
    });
  }
  MatrixTags tags;
  tags.symmetric = DecodeTristate(d, "symmetric");
  tags.positive_definite = DecodeTristate(d, "positive_definite");
  tags.p_matrix = DecodeTristate(d, "p_matrix");
  const std::size_t expected_at = d.pos();
  const std::uint8_t expected = d.U8("expected");
  if (expected > 2) {
    d.FailAt(expected_at, "expected",
             "value " + std::to_string(expected) + " is not 0 (unknown), 1 (solvable) or 2 (infeasible)");
  }
  std::optional<std::uint64_t> seed;
  if (flags & kHasSeed) seed = d.U64("seed");
  Vector solution;
  if (flags & kHasSolution) {
    d.Need(n, 8, "solution");
    solution.resize(M.n);
    d.F64s(solution.data(), count, [&](std::size_t i, double v, std::size_t at) {
      if (!std::isfinite(v)) d.FailAt(at, Index("solution", i), std::isnan(v) ? "is NaN" : "is infinite");
    });
  }
  const std::size_t tags_at = d.pos();
  const std::uint32_t tag_count = d.U32("tag count");
  if (inherits && tag_count != 0) {
    d.FailAt(tags_at, "tag count", "must be 0 when flag bit 4 (continue the previous problem) is set");
  }
  d.Need(tag_count, 4, "tags");  // each tag takes at least its 4-byte length
  std::vector<std::string> labels;
  labels.reserve(tag_count);
  for (std::uint32_t i = 0; i < tag_count; ++i) labels.push_back(d.Str(Index("tag", i)));
  const std::uint32_t entries = d.U32("metadata count");
  d.Need(entries, 8, "metadata");
  std::map<std::string, std::string> metadata;
  for (std::uint32_t i = 0; i < entries; ++i) {
    const std::size_t at = d.pos();
    std::string key = d.Str(Index("metadata key", i));
    std::string value = d.Str(Index("metadata value", i));
    if (!metadata.emplace(std::move(key), std::move(value)).second) {
      d.FailAt(at, Index("metadata key", i), "key repeated");
    }
  }
  if (inherits) {
    // The previous problem's source, tags and metadata, with the entries stored here replacing or adding to its own.
    source = previous->source;
    labels = previous->tags;
    std::uint64_t bytes = source.size();
    for (const std::string& t : labels) bytes += t.size();
    for (const auto& [key, value] : previous->metadata) {
      if (metadata.emplace(key, value).second) bytes += key.size() + value.size();
    }
    *inherited_bytes += bytes;
  }
  ReferenceSolution reference;  // version 1 stores none: Certificate::kNone
  if (version >= 2) reference = DecodeReference(d, n, M.n);
  d.ExpectEnd();
  std::optional<BoxMLCP> problem;
  try {
    if (M.sparse) {
      problem.emplace(M.sp, std::move(q), std::move(l), std::move(u), std::move(name));
    } else {
      problem.emplace(M.dense, std::move(q), std::move(l), std::move(u), std::move(name));
    }
  } catch (const InvalidInputError& e) {
    d.FailAt(index_at, "", e.what());
  }
  return LibraryProblem{std::move(id),       std::move(source), std::move(*problem),   tags,
                        std::move(labels),   seed,              static_cast<ExpectedOutcome>(expected),
                        std::move(solution), std::move(metadata), std::move(reference)};
}

struct Decoded {
  ProblemSet set;
  ProblemSetFileInfo info;
};

[[noreturn]] void FailAtByte(const std::string& file, std::size_t offset, const std::string& what) {
  throw InvalidInputError("problem set '" + file + "': " + what + " at byte " + std::to_string(offset));
}

const char* KindText(ProblemSetKind kind) {
  return kind == ProblemSetKind::kAvi ? "a set of AVIs (set kind 1)" : "a set of box-MLCPs (set kind 0)";
}

struct Header {
  std::uint32_t version = 0;
  ProblemSetKind kind = ProblemSetKind::kBoxMlcp;
};

// The 16-byte header: magic, a readable version, and the reserved field (0 before version 4, the set kind after).
Header CheckHeader(std::string_view data, const std::string& file) {
  const auto fail = [&](std::size_t offset, const std::string& what) { FailAtByte(file, offset, what); };
  if (data.empty()) fail(0, "empty file");
  if (data.size() < sizeof kMagic || std::memcmp(data.data(), kMagic, sizeof kMagic) != 0) {
    if (data.size() < sizeof kMagic && std::memcmp(data.data(), kMagic, data.size()) == 0) {
      fail(data.size(), "truncated: " + std::to_string(data.size()) + " byte(s), shorter than the " +
                            std::to_string(kHeaderBytes) + "-byte header");
    }
    fail(0, "not a smcbench problem-set file (wrong magic bytes; expected \\x89SMCPS\\r\\n)");
  }
  if (data.size() < kHeaderBytes) {
    fail(data.size(), "truncated: " + std::to_string(data.size()) + " byte(s), shorter than the " +
                          std::to_string(kHeaderBytes) + "-byte header");
  }
  Header h;
  h.version = static_cast<std::uint32_t>(LoadLE(data.data() + 8, 4));
  if (h.version < kOldestReadableProblemSetFormatVersion || h.version > kNewestReadableProblemSetFormatVersion) {
    fail(8, "format version " + std::to_string(h.version) + " is not supported: this build reads versions " +
                std::to_string(kOldestReadableProblemSetFormatVersion) + " to " +
                std::to_string(kNewestReadableProblemSetFormatVersion) +
                (h.version > kNewestReadableProblemSetFormatVersion ? " (the file was written by a newer smcbench)"
                                                                    : ""));
  }
  const std::uint64_t reserved = LoadLE(data.data() + 12, 4);
  if (h.version < 4) {
    if (reserved != 0) fail(12, "reserved header field is " + Hex(reserved) + ", expected 0");
  } else if (reserved > static_cast<std::uint32_t>(ProblemSetKind::kAvi)) {
    fail(12, "set kind " + std::to_string(reserved) + " is unknown (0 box-MLCPs, 1 AVIs)");
  } else {
    h.kind = static_cast<ProblemSetKind>(reserved);
  }
  return h;
}

struct Frame {
  Header header;
  std::size_t end_at = 0;  // offset of the end record
};

// Header, framing (the records walked by their lengths only, up to the end record) and checksum, before any field
// is interpreted.
Frame CheckFrame(std::string_view data, const std::string& file) {
  const auto fail = [&](std::size_t offset, const std::string& what) { FailAtByte(file, offset, what); };
  if (data.size() > kMaxProblemSetFileBytes) {
    fail(0, "file of " + std::to_string(data.size()) + " bytes exceeds the limit of " +
                std::to_string(kMaxProblemSetFileBytes));
  }
  Frame frame;
  frame.header = CheckHeader(data, file);

  // ---- framing: walk the records to the end record, checking only their lengths.
  std::size_t pos = kHeaderBytes;
  std::uint64_t records = 0;
  while (true) {
    if (pos == data.size()) {
      fail(pos, "truncated: the file ends after " + std::to_string(records) + " record(s) without an end record");
    }
    if (data.size() - pos < kRecordHeaderBytes) {
      fail(pos, "truncated: " + std::to_string(data.size() - pos) + " byte(s) left, too few for a record header");
    }
    const auto kind = static_cast<std::uint8_t>(data[pos]);
    const std::uint64_t length = LoadLE(data.data() + pos + 1, 8);
    const std::size_t body = pos + kRecordHeaderBytes;
    if (length > data.size() - body) {
      fail(pos, std::string("truncated or corrupt: ") + KindName(kind) + " #" + std::to_string(records) +
                    " declares " + std::to_string(length) + " byte(s) but only " +
                    std::to_string(data.size() - body) + " remain");
    }
    ++records;
    if (kind == kEndRecord) {
      frame.end_at = pos;
      if (length != kEndBodyBytes) {
        fail(pos, "end record has " + std::to_string(length) + " byte(s), expected " + std::to_string(kEndBodyBytes));
      }
      const std::size_t file_end = body + kEndBodyBytes;
      if (file_end != data.size()) {
        fail(file_end, std::to_string(data.size() - file_end) + " unexpected byte(s) after the end record");
      }
      break;
    }
    pos = body + static_cast<std::size_t>(length);
  }
  // ---- checksum, before interpreting anything.
  const std::uint64_t stored = LoadLE(data.data() + data.size() - 8, 8);
  const std::uint64_t computed = ProblemSetChecksum(data.substr(0, data.size() - 8));
  if (stored != computed) {
    fail(data.size() - 8, "checksum mismatch (stored " + Hex(stored) + ", computed " + Hex(computed) +
                              "): the file is corrupt");
  }
  return frame;
}

// The record walk both set kinds share: the set record first and only once (its name and description into *name
// and *description), every other record handed to on_record(kind, pos, body, length), up to the end record.
template <typename OnRecord>
void WalkRecords(std::string_view data, const Frame& frame, const std::string& file, std::string* name,
                 std::string* description, OnRecord on_record) {
  bool have_set = false;
  std::size_t pos = kHeaderBytes;
  while (pos < frame.end_at) {
    const auto kind = static_cast<std::uint8_t>(data[pos]);
    const std::size_t body = pos + kRecordHeaderBytes;
    const auto length = static_cast<std::size_t>(LoadLE(data.data() + pos + 1, 8));
    if (kind != kSetRecord && !have_set) FailAtByte(file, pos, std::string(KindName(kind)) + " before the set record");
    if (kind == kSetRecord) {
      if (have_set) FailAtByte(file, pos, "a second set record");
      Decoder d(data, body, body + length, file, "set record");
      *name = d.Str("name");
      *description = d.Str("description");
      d.ExpectEnd();
      have_set = true;
    } else {
      on_record(kind, pos, body, length);
    }
    pos = body + length;
  }
  if (!have_set) FailAtByte(file, frame.end_at, "no set record before the end record");
}

// The end record's counts checked against what was decoded; returns them (matrices, problems). what: "problems" or
// "AVIs", for the message.
std::pair<std::uint64_t, std::uint64_t> CheckEndCounts(std::string_view data, const Frame& frame,
                                                       const std::string& file, std::size_t matrices_read,
                                                       std::size_t problems_read, const char* what) {
  const std::uint64_t matrices = LoadLE(data.data() + frame.end_at + kRecordHeaderBytes, 8);
  const std::uint64_t problems = LoadLE(data.data() + frame.end_at + kRecordHeaderBytes + 8, 8);
  if (matrices != matrices_read || problems != problems_read) {
    FailAtByte(file, frame.end_at,
               "end record counts " + std::to_string(matrices) + " matrices and " + std::to_string(problems) + " " +
                   what + " but the file holds " + std::to_string(matrices_read) + " and " +
                   std::to_string(problems_read));
  }
  return {matrices, problems};
}

Decoded Decode(std::string_view data, const std::string& file) {
  const auto fail = [&](std::size_t offset, const std::string& what) { FailAtByte(file, offset, what); };
  const Frame frame = CheckFrame(data, file);
  const std::uint32_t version = frame.header.version;
  if (frame.header.kind != ProblemSetKind::kBoxMlcp) {
    fail(12, std::string(KindText(frame.header.kind)) + ", not of box-MLCPs (read it as an AVI set)");
  }
  Decoded out;
  out.info.version = version;
  out.info.kind = frame.header.kind;
  out.info.bytes = data.size();

  // ---- records
  std::vector<TableMatrix> table;
  std::vector<TableBounds> bounds_table;
  std::uint64_t expanded = 0;  // bytes of matrix data once every problem holds its own copy
  std::uint64_t inherited = 0;  // bytes of text the problems take from the one before them (version 3)
  std::unordered_set<std::string> ids;
  WalkRecords(data, frame, file, &out.set.name, &out.set.description,
              [&](std::uint8_t kind, std::size_t pos, std::size_t body, std::size_t length) {
    switch (kind) {
      case kMatrixRecord: {
        Decoder d(data, body, body + length, file, "matrix #" + std::to_string(table.size()));
        table.push_back(DecodeMatrix(d));
        break;
      }
      case kBoundsRecord: {
        if (version < 3) {
          fail(pos, "unknown record kind " + std::to_string(kind) + " in a version-" + std::to_string(version) +
                        " file (bounds records exist from version 3 on)");
        }
        Decoder d(data, body, body + length, file, "bounds #" + std::to_string(bounds_table.size()));
        bounds_table.push_back(DecodeBounds(d));
        break;
      }
      case kProblemRecord: {
        Decoder d(data, body, body + length, file, "problem #" + std::to_string(out.set.problems.size()));
        LibraryProblem p = DecodeProblem(d, table, bounds_table, version,
                                         out.set.problems.empty() ? nullptr : &out.set.problems.back(), &inherited);
        if (inherited > kMaxInheritedTextBytes) {
          fail(body, "the problems so far take " + std::to_string(inherited) + " bytes of source, tags and metadata " +
                         "from the problems before them, above the limit of " + std::to_string(kMaxInheritedTextBytes));
        }
        const BoxMLCP& b = p.problem;
        expanded += b.is_sparse() ? static_cast<std::uint64_t>(b.sparse_matrix().nonZeros()) * 12
                                  : static_cast<std::uint64_t>(b.size()) * static_cast<std::uint64_t>(b.size()) * 8;
        if (expanded > kMaxExpandedMatrixBytes) {
          fail(body, "the problems so far hold " + std::to_string(expanded) + " bytes of matrix data in memory " +
                         "(each problem owns a copy of its shared M), above the limit of " +
                         std::to_string(kMaxExpandedMatrixBytes));
        }
        if (!ids.insert(p.id).second) fail(body, "duplicate problem id '" + QuoteForMessage(p.id) + "'");
        if (p.id.empty()) fail(body, "problem #" + std::to_string(out.set.problems.size()) + " has an empty id");
        out.set.problems.push_back(std::move(p));
        break;
      }
      default:
        fail(pos, "unknown record kind " + std::to_string(kind) +
                      " (this build knows 1 set, 2 matrix, 3 problem, 4 end, 5 bounds; 6 AVI in a set of AVIs)");
    }
  });
  std::tie(out.info.matrices, out.info.problems) =
      CheckEndCounts(data, frame, file, table.size(), out.set.problems.size(), "problems");
  return out;
}

// ---- sets of AVIs

// A matrix record of an AVI set: storage 2, rows × cols, finite values (column-major).
DenseMatrix DecodeAviMatrix(Decoder& d) {
  const std::size_t storage_at = d.pos();
  const std::uint8_t storage = d.U8("storage");
  if (storage != kDenseRectangularStorage) {
    d.FailAt(storage_at, "storage",
             "storage " + std::to_string(storage) + " in a set of AVIs (its matrices are 2, dense rows x cols)");
  }
  const std::size_t rows_at = d.pos();
  const std::uint64_t rows = d.U64("rows");
  const std::size_t cols_at = d.pos();
  const std::uint64_t cols = d.U64("cols");
  if (rows < 1 || rows > kMaxDimension) {
    d.FailAt(rows_at, "rows", std::to_string(rows) + " is outside [1, " + std::to_string(kMaxDimension) + "]");
  }
  if (cols < 1 || cols > kMaxDimension) {
    d.FailAt(cols_at, "cols", std::to_string(cols) + " is outside [1, " + std::to_string(kMaxDimension) + "]");
  }
  // rows·cols values, checked without forming the product (it may overflow).
  if (rows > d.remaining() / 8 / cols) {
    d.Fail("values", "a dense " + std::to_string(rows) + "x" + std::to_string(cols) + " matrix needs more than the " +
                         std::to_string(d.remaining()) + " byte(s) left in the record (corrupt size field)");
  }
  DenseMatrix A(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(cols));
  d.F64s(A.data(), static_cast<std::size_t>(rows * cols), [&](std::size_t i, double v, std::size_t at) {
    if (!std::isfinite(v)) {
      d.FailAt(at, "(" + std::to_string(i % rows) + "," + std::to_string(i / rows) + ")",
               std::isnan(v) ? "is NaN" : "is infinite");
    }
  });
  d.ExpectEnd();
  return A;
}

// A row count (m or p) of an AVI record: at most 2^31 − 1.
std::uint64_t DecodeRowCount(Decoder& d, const char* field) {
  const std::size_t at = d.pos();
  const std::uint64_t count = d.U64(field);
  if (count > kMaxDimension) {
    d.FailAt(at, field, std::to_string(count) + " exceeds " + std::to_string(kMaxDimension));
  }
  return count;
}

// A matrix index of an AVI record, checked against the table and the shape the record gives.
const DenseMatrix& DecodeAviMatrixIndex(Decoder& d, const std::vector<DenseMatrix>& table, const char* field,
                                        std::uint64_t rows, std::uint64_t cols) {
  const std::size_t at = d.pos();
  const std::uint64_t index = d.U64(field);
  if (index >= table.size()) {
    d.FailAt(at, field, "refers to matrix " + std::to_string(index) + " but only " + std::to_string(table.size()) +
                            " precede this AVI");
  }
  const DenseMatrix& A = table[static_cast<std::size_t>(index)];
  if (static_cast<std::uint64_t>(A.rows()) != rows || static_cast<std::uint64_t>(A.cols()) != cols) {
    d.FailAt(at, field, "matrix " + std::to_string(index) + " is " + std::to_string(A.rows()) + "x" +
                            std::to_string(A.cols()) + " but the AVI needs " + std::to_string(rows) + "x" +
                            std::to_string(cols));
  }
  return A;
}

// count finite doubles into v (the count is checked against the record first).
void DecodeFiniteVector(Decoder& d, const char* field, std::uint64_t count, Vector* v) {
  d.Need(count, 8, field);
  v->resize(static_cast<Eigen::Index>(count));
  d.F64s(v->data(), static_cast<std::size_t>(count), [&](std::size_t i, double x, std::size_t at) {
    if (!std::isfinite(x)) d.FailAt(at, Index(field, i), std::isnan(x) ? "is NaN" : "is infinite");
  });
}

// *expanded grows by the bytes of M, H and E this AVI owns once read.
AviLibraryProblem DecodeAvi(Decoder& d, const std::vector<DenseMatrix>& table, std::uint64_t* expanded) {
  AviLibraryProblem out;
  out.id = d.Str("id");
  d.set_where(d.where() + " ('" + QuoteForMessage(out.id) + "')");
  out.source = d.Str("source");
  const std::size_t flags_at = d.pos();
  const std::uint8_t flags = d.U8("flags");
  if (flags & ~kKnownAviFlags) d.FailAt(flags_at, "flags", "unknown flag bits " + Hex(flags & ~kKnownAviFlags));
  std::string name = (flags & kAviNameIsId) ? out.id : d.Str("name");
  const std::size_t n_at = d.pos();
  const std::uint64_t n = d.U64("n");
  if (n < 1 || n > kMaxDimension) {
    d.FailAt(n_at, "n", "n = " + std::to_string(n) + " is outside [1, " + std::to_string(kMaxDimension) + "]");
  }
  const DenseMatrix& M = DecodeAviMatrixIndex(d, table, "M index", n, n);
  Vector q, K, f;
  DecodeFiniteVector(d, "q", n, &q);
  const std::uint64_t m = DecodeRowCount(d, "m");
  const DenseMatrix* H = m > 0 ? &DecodeAviMatrixIndex(d, table, "H index", m, n) : nullptr;
  DecodeFiniteVector(d, "K", m, &K);
  const std::uint64_t p = DecodeRowCount(d, "p");
  const DenseMatrix* E = p > 0 ? &DecodeAviMatrixIndex(d, table, "E index", p, n) : nullptr;
  DecodeFiniteVector(d, "f", p, &f);
  if (n + m + p > kMaxDimension) d.Fail("p", "n + m + p exceeds " + std::to_string(kMaxDimension));
  const std::size_t expected_at = d.pos();
  const std::uint8_t expected = d.U8("expected");
  if (expected > 2) {
    d.FailAt(expected_at, "expected",
             "value " + std::to_string(expected) + " is not 0 (unknown), 1 (solvable) or 2 (infeasible)");
  }
  out.expected = static_cast<ExpectedOutcome>(expected);
  const std::uint32_t tag_count = d.U32("tag count");
  d.Need(tag_count, 4, "tags");  // each tag takes at least its 4-byte length
  out.tags.reserve(tag_count);
  for (std::uint32_t i = 0; i < tag_count; ++i) out.tags.push_back(d.Str(Index("tag", i)));
  const std::uint32_t entries = d.U32("metadata count");
  d.Need(entries, 8, "metadata");
  for (std::uint32_t i = 0; i < entries; ++i) {
    const std::size_t at = d.pos();
    std::string key = d.Str(Index("metadata key", i));
    std::string value = d.Str(Index("metadata value", i));
    if (!out.metadata.emplace(std::move(key), std::move(value)).second) {
      d.FailAt(at, Index("metadata key", i), "key repeated");
    }
  }
  AviReference& r = out.reference;
  const std::size_t monotone_at = d.pos();
  const std::uint8_t monotone = d.U8("strictly monotone");
  if (monotone > 2) {
    d.FailAt(monotone_at, "strictly monotone",
             "value " + std::to_string(monotone) + " is not 0 (not decided), 1 (no) or 2 (yes)");
  }
  r.strictly_monotone = static_cast<MatrixClassAnswer>(monotone);
  r.reduced = DecodeReference(d, n + m + p, static_cast<Eigen::Index>(n + m + p));
  if (r.verified()) {
    r.solution.lambda = r.reduced.z.head(static_cast<Eigen::Index>(n));
    DecodeFiniteVector(d, "reference mu", m, &r.solution.mu);
    DecodeFiniteVector(d, "reference nu", p, &r.solution.nu);
  } else if (flags & kAviLambdaUnique) {
    d.FailAt(flags_at, "flags", "bit 1 (lambda* unique) without a verified reference");
  }
  r.lambda_unique = (flags & kAviLambdaUnique) != 0;
  d.ExpectEnd();
  // In memory every AVI owns its matrices: the table's sharing is bounded as for box sets.
  *expanded += (n * n + (m + p) * n) * 8;
  if (*expanded > kMaxExpandedMatrixBytes) {
    d.FailAt(n_at, "", "the AVIs so far hold " + std::to_string(*expanded) + " bytes of matrix data in memory " +
                           "(each owns a copy of its shared M, H, E), above the limit of " +
                           std::to_string(kMaxExpandedMatrixBytes));
  }
  try {
    out.problem = std::make_shared<const AffineVI>(M, std::move(q), H ? *H : DenseMatrix(0, M.cols()), std::move(K),
                                                   E ? *E : DenseMatrix(0, M.cols()), std::move(f), std::move(name));
  } catch (const InvalidInputError& e) {
    d.FailAt(n_at, "", e.what());  // the AffineVI's own checks: a zero row, P empty
  }
  if (out.expected == ExpectedOutcome::kInfeasible && r.verified()) {
    d.FailAt(expected_at, "expected", "is infeasible but the reference is a verified solution");
  }
  if (out.expected == ExpectedOutcome::kInfeasible && out.problem->boundedness() == PolytopeBoundedness::kBounded) {
    d.FailAt(expected_at, "expected", "is infeasible, but P is bounded, so the AVI has a solution");
  }
  return out;
}

struct DecodedAvis {
  AviProblemSet set;
  ProblemSetFileInfo info;
};

DecodedAvis DecodeAvis(std::string_view data, const std::string& file) {
  const auto fail = [&](std::size_t offset, const std::string& what) { FailAtByte(file, offset, what); };
  const Frame frame = CheckFrame(data, file);
  if (frame.header.kind != ProblemSetKind::kAvi) {
    fail(12, std::string(KindText(frame.header.kind)) + " (format version " + std::to_string(frame.header.version) +
                 "), not of AVIs");
  }
  DecodedAvis out;
  out.info.version = frame.header.version;
  out.info.kind = frame.header.kind;
  out.info.bytes = data.size();
  std::vector<DenseMatrix> table;
  std::uint64_t expanded = 0;
  std::unordered_set<std::string> ids;
  WalkRecords(data, frame, file, &out.set.name, &out.set.description,
              [&](std::uint8_t kind, std::size_t pos, std::size_t body, std::size_t length) {
    switch (kind) {
      case kMatrixRecord: {
        Decoder d(data, body, body + length, file, "matrix #" + std::to_string(table.size()));
        table.push_back(DecodeAviMatrix(d));
        break;
      }
      case kAviRecord: {
        Decoder d(data, body, body + length, file, "AVI #" + std::to_string(out.set.problems.size()));
        AviLibraryProblem p = DecodeAvi(d, table, &expanded);
        if (p.id.empty()) fail(body, "AVI #" + std::to_string(out.set.problems.size()) + " has an empty id");
        if (!ids.insert(p.id).second) fail(body, "duplicate AVI id '" + QuoteForMessage(p.id) + "'");
        out.set.problems.push_back(std::move(p));
        break;
      }
      default:
        fail(pos, "record kind " + std::to_string(kind) + " in a set of AVIs (it holds 1 set, 2 matrix, 6 AVI, " +
                      "4 end)");
    }
  });
  std::tie(out.info.matrices, out.info.problems) =
      CheckEndCounts(data, frame, file, table.size(), out.set.problems.size(), "AVIs");
  return out;
}

std::string ReadAll(std::istream& in, const std::string& name, std::size_t expected_size = 0) {
  std::string data;
  data.reserve(expected_size);
  char chunk[1 << 16];
  while (in) {
    in.read(chunk, sizeof chunk);
    data.append(chunk, static_cast<std::size_t>(in.gcount()));
    if (data.size() > kMaxProblemSetFileBytes) {
      throw InvalidInputError("problem set '" + name + "': input exceeds the limit of " +
                              std::to_string(kMaxProblemSetFileBytes) + " bytes");
    }
  }
  if (in.bad()) throw InvalidInputError("problem set '" + name + "': read error");
  return data;
}

std::string ReadFileBytes(const std::string& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw InvalidInputError("problem set '" + path + "': is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw InvalidInputError("problem set '" + path + "': cannot open: " + std::generic_category().message(errno));
  }
  const std::uintmax_t size = fs::file_size(path, ec);
  if (!ec && size > kMaxProblemSetFileBytes) {
    throw InvalidInputError("problem set '" + path + "': file of " + std::to_string(size) +
                            " bytes exceeds the limit of " + std::to_string(kMaxProblemSetFileBytes));
  }
  return ReadAll(in, path, ec ? 0 : static_cast<std::size_t>(size));
}

}  // namespace

std::uint64_t ProblemSetChecksum(std::string_view bytes) {
  Fnv1a64 h;
  h.Update(bytes.data(), bytes.size());
  return h.value();
}

void FixProblemSetChecksum(std::string* bytes) {
  if (bytes->size() < 8) return;
  const std::size_t at = bytes->size() - 8;
  StoreLE(bytes->data() + at, ProblemSetChecksum(std::string_view(*bytes).substr(0, at)), 8);
}

ProblemSet ReadProblemSetBytes(std::string_view bytes, const std::string& name_for_errors) {
  return Decode(bytes, name_for_errors).set;
}

ProblemSet ReadProblemSet(std::istream& in, const std::string& name_for_errors) {
  const std::string data = ReadAll(in, name_for_errors);
  return Decode(data, name_for_errors).set;
}

ProblemSet ReadProblemSetFile(const std::string& path) {
  const std::string data = ReadFileBytes(path);
  return Decode(data, path).set;
}

ProblemSet ReadProblemSetFile(const std::string& path, ProblemSetFileInfo* info) {
  const std::string data = ReadFileBytes(path);
  Decoded d = Decode(data, path);
  if (info) *info = d.info;
  return std::move(d.set);
}

ProblemSetKind ReadProblemSetKind(const std::string& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw InvalidInputError("problem set '" + path + "': is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw InvalidInputError("problem set '" + path + "': cannot open: " + std::generic_category().message(errno));
  }
  char header[kHeaderBytes];
  in.read(header, sizeof header);
  return CheckHeader(std::string_view(header, static_cast<std::size_t>(in.gcount())), path).kind;
}

AviProblemSet ReadAviProblemSetBytes(std::string_view bytes, const std::string& name_for_errors) {
  return DecodeAvis(bytes, name_for_errors).set;
}

AviProblemSet ReadAviProblemSetFile(const std::string& path, ProblemSetFileInfo* info) {
  const std::string data = ReadFileBytes(path);
  DecodedAvis d = DecodeAvis(data, path);
  if (info) *info = d.info;
  return std::move(d.set);
}

}  // namespace smcbench

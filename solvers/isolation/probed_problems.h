// Why: the siconos-* adapters run a problem's first solve in their isolation worker (the probe) and later solves of
// the same problem in this process; this remembers which problems have come back from a probe, exactly and within
// a fixed memory bound. No Siconos header (tests: ProbedProblemsTest in siconos_solver_test.cc).
//
// A problem is the exact bytes sent to Siconos (the request with the options that reach it, M, q, the bounds, the
// start point), given as a list of parts. A cheap 64-bit hash finds the candidates, a full comparison against the
// stored copy decides: a hash collision can never let a problem that was not probed skip its probe. The copies are
// bounded: at most max_problems problems and max_bytes bytes of copies in all; remembering one more forgets the
// oldest first, and a problem larger than max_bytes is never remembered (it is probed on every solve). Find()
// allocates nothing; Stage() and Commit() (the probe's path, already paying for a round trip to the worker) may.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

namespace smcbench {

class ProbedProblems {
 public:
  struct Part {
    const void* data;
    std::size_t bytes;
  };
  // A view of the parts of one problem, in order (an array that outlives the call).
  class Parts {
   public:
    template <std::size_t N>
    Parts(const std::array<Part, N>& parts) : begin_(parts.data()), end_(parts.data() + N) {}  // NOLINT: implicit
    const Part* begin() const { return begin_; }
    const Part* end() const { return end_; }

   private:
    const Part* begin_;
    const Part* end_;
  };
  // What Siconos wrote to the console during the probe: nothing, through the C streams (printf, fprintf(stderr)),
  // or to descriptors 1 and 2 directly (LAPACK's Fortran messages). An in-process solve of the same problem always
  // silences the C streams (swapping FILE pointers, no system call) and redirects the descriptors (system calls) only
  // after kDescriptors.
  enum class Console { kSilent, kStdio, kDescriptors };
  struct Outcome {
    Console console = Console::kSilent;
    double seconds = 0.0;  // the probe's wall time: a later solve under a shorter time limit goes to the worker
  };
  using HashFunction = std::uint64_t (*)(Parts parts);

  explicit ProbedProblems(HashFunction hash = &Hash) : hash_(hash) {}

  // Bounds on what is remembered; shrinking them forgets the oldest problems at once.
  void set_limits(int max_problems, std::size_t max_bytes) {
    max_problems_ = max_problems < 0 ? 0 : static_cast<std::size_t>(max_problems);
    max_bytes_ = max_bytes;
    EvictUntilRoomFor(0);
  }

  // The probe's outcome if exactly these bytes were probed (and not forgotten since), else nullptr. A repeated
  // solve usually asks for the problem found last: that one is compared first, without hashing; then the others,
  // newest first, by hash. No allocation.
  const Outcome* Find(Parts parts) const {
    const std::size_t bytes = TotalBytes(parts);
    if (last_found_ < entries_.size()) {
      const Entry& e = entries_[last_found_];
      if (e.bytes.size() == bytes && SameBytes(e.bytes, parts)) return &e.outcome;
    }
    const std::uint64_t h = hash_(parts);
    for (std::size_t i = entries_.size(); i-- > 0;) {
      const Entry& e = entries_[i];
      if (e.hash == h && e.bytes.size() == bytes && SameBytes(e.bytes, parts)) {
        last_found_ = i;
        return &e.outcome;
      }
    }
    return nullptr;
  }

  // Copies the bytes of a problem about to be probed (the call overwrites some of them, e.g. the start point).
  void Stage(Parts parts) {
    staged_hash_ = hash_(parts);
    staged_.resize(TotalBytes(parts));
    std::size_t at = 0;
    for (const Part& p : parts) {
      if (p.bytes > 0) std::memcpy(staged_.data() + at, p.data, p.bytes);
      at += p.bytes;
    }
    has_staged_ = true;
  }
  // The staged problem's probe came back normally: remember it. False if it is larger than max_bytes (or
  // max_problems is 0), or nothing was staged.
  bool Commit(const Outcome& outcome) {
    if (!has_staged_) return false;
    has_staged_ = false;
    if (max_problems_ == 0 || staged_.size() > max_bytes_) return false;
    EvictUntilRoomFor(staged_.size());
    Entry e;
    e.hash = staged_hash_;
    e.bytes.swap(staged_);
    e.outcome = outcome;
    bytes_ += e.bytes.size();
    entries_.push_back(std::move(e));
    last_found_ = entries_.size() - 1;  // solved again next, most likely
    return true;
  }
  // The staged problem's probe did not come back normally (crash, signal, deadline): not remembered.
  void Discard() { has_staged_ = false; }

  void Clear() {
    entries_.clear();
    last_found_ = kNone;
    bytes_ = 0;
    has_staged_ = false;
  }
  std::size_t size() const { return entries_.size(); }
  std::size_t bytes() const { return bytes_; }

  // 64-bit hash of the concatenated parts, 8 bytes at a time (a multiply and a shift per word), each part's length
  // mixed in. Not cryptographic, and need not be: equal hashes are always confirmed by a full comparison.
  static std::uint64_t Hash(Parts parts) {
    std::uint64_t h = 0x9E3779B97F4A7C15ull;
    for (const Part& p : parts) {
      const auto* b = static_cast<const unsigned char*>(p.data);
      std::size_t i = 0;
      for (; i + 8 <= p.bytes; i += 8) {
        std::uint64_t w;
        std::memcpy(&w, b + i, 8);
        h = Mix(h ^ w);
      }
      std::uint64_t tail = 0;
      if (i < p.bytes) std::memcpy(&tail, b + i, p.bytes - i);
      h = Mix(h ^ tail ^ (static_cast<std::uint64_t>(p.bytes) << 40));
    }
    return h;
  }

 private:
  struct Entry {
    std::uint64_t hash = 0;
    std::vector<unsigned char> bytes;
    Outcome outcome;
  };

  static std::uint64_t Mix(std::uint64_t x) {
    x *= 0xff51afd7ed558ccdull;
    return x ^ (x >> 33);
  }
  static std::size_t TotalBytes(Parts parts) {
    std::size_t n = 0;
    for (const Part& p : parts) n += p.bytes;
    return n;
  }
  static bool SameBytes(const std::vector<unsigned char>& stored, Parts parts) {
    std::size_t at = 0;
    for (const Part& p : parts) {
      if (p.bytes > 0 && std::memcmp(stored.data() + at, p.data, p.bytes) != 0) return false;
      at += p.bytes;
    }
    return true;
  }
  // Forgets the oldest problems until one more of `bytes` fits both bounds.
  void EvictUntilRoomFor(std::size_t bytes) {
    std::size_t drop = 0;
    std::size_t kept_bytes = bytes_;
    const std::size_t slots = bytes > 0 ? 1 : 0;
    while (drop < entries_.size() &&
           (entries_.size() - drop + slots > max_problems_ || kept_bytes + bytes > max_bytes_)) {
      kept_bytes -= entries_[drop].bytes.size();
      ++drop;
    }
    if (drop == 0) return;
    entries_.erase(entries_.begin(), entries_.begin() + static_cast<std::ptrdiff_t>(drop));
    bytes_ = kept_bytes;
    last_found_ = last_found_ != kNone && last_found_ >= drop ? last_found_ - drop : kNone;
  }

  static constexpr std::size_t kNone = static_cast<std::size_t>(-1);

  HashFunction hash_;
  std::vector<Entry> entries_;  // oldest first
  mutable std::size_t last_found_ = kNone;  // index of the entry Find (or Commit) matched last
  std::size_t bytes_ = 0;       // total size of the stored copies
  std::size_t max_problems_ = 32;
  std::size_t max_bytes_ = std::size_t{64} << 20;
  std::vector<unsigned char> staged_;
  std::uint64_t staged_hash_ = 0;
  bool has_staged_ = false;
};

}  // namespace smcbench

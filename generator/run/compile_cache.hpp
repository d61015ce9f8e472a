// rotgen — compile generated C++ with the system compiler into a cached shared object and load it.
//
// The cache key is a hash of the source without its comment lines, the compiler's identity
// (`$CXX --version`) and the flags, so a changed model, option, generator or compiler builds anew,
// while the same code compiles once however its comments differ (a generated header's comments
// name the model file as its path was spelt: `sat.yaml` and `/abs/sat.yaml` share one library).
// Cache directory: $ROTGEN_CACHE_DIR, else $XDG_CACHE_HOME/rotgen, else ~/.cache/rotgen.
#pragma once

#include <cstdint>
#include <string>

namespace rotgen {

class loaded_library {
  public:
    loaded_library() = default;
    loaded_library(const loaded_library&) = delete;
    loaded_library& operator=(const loaded_library&) = delete;
    loaded_library(loaded_library&& other) noexcept;
    loaded_library& operator=(loaded_library&& other) noexcept;
    ~loaded_library();

    // The address of an exported (extern "C") symbol; throws if it is missing.
    void* symbol(const std::string& name) const;
    const std::string& path() const { return m_path; }
    bool was_cached() const { return m_cached; }

  private:
    friend loaded_library compile_and_load(const std::string&, const std::string&,
                                           const std::string&);
    void* m_handle = nullptr;
    std::string m_path;
    bool m_cached = false;
};

std::string cache_directory();

// cache_directory(), created; throws user_error naming it (and ROTGEN_CACHE_DIR) if it cannot be
// made or written: a read-only folder, one under a regular file, a HOME that does not exist.
std::string usable_cache_directory();

// `$CXX --version` (once per process): part of every cache key, so another compiler builds anew.
// Throws std::runtime_error if the compiler does not run.
const std::string& compiler_identity();

// The flags that let compiled code use this machine's vector instructions: "-mavx2 -mfma" where
// the CPU has AVX2 and FMA, with "-ffp-contract=off", or "-ffp-contract=fast" if `fused` (products
// fused into sums); "-ffp-contract=off" or "=fast" alone elsewhere. `target` gets their name
// ("avx2+fma" or "sse2"). Even without contraction the code is not the portable build's bit for
// bit: GCC 12's SLP vectoriser emits vfmaddsub despite -ffp-contract=off (the heavy top's body-form
// rhs, half of 100,000 random states off by an ulp). For the bench driver, and fused for the lane
// kernels, whose arithmetic is their own anyway (vector sin and cos, shared steps).
std::string host_vector_flags(std::string* target = nullptr, bool fused = false);

// host_vector_flags(target, true), or where the CPU has AVX-512 (F, DQ, VL, BW) and `wide`, its
// 8-wide vectors: "-mavx512f -mavx512dq -mavx512vl -mavx512bw -mavx2 -mfma -ffp-contract=fast",
// target "avx512+fma". For the lane kernels of a `taylor` scene: one heavy-top expansion in a
// batch of 8 took 45 ns a lane against 131 in a batch of 4 (bench/results/taylor_kernel.md),
// while a DOP853 lane sweep took 10% longer with them (docs/design-notes.md).
std::string host_lane_vector_flags(std::string* target, bool wide);

// The flags that let compiled code use this machine's vectors with the portable build's bits:
// "-mavx2" where the CPU has AVX2, else none. Without -mfma no instruction can fuse a product
// into a sum, and vector + - * / round as the scalar ones do (tests/run/test_kernel_flags.cpp).
// The scalar kernels of a `taylor` scene use them: the recurrences' sums run in 4-wide vectors
// (one heavy-top expansion 281 against 551 ns). The other methods' kernels stay portable: a
// DOP853 sweep took 25% longer with any VEX-encoded code (docs/design-notes.md).
std::string host_exact_vector_flags();

// `source` without the lines whose first non-blank characters are "//": what the cache keys on.
std::string without_comment_lines(const std::string& source);

// Compiles `source` (a complete translation unit) unless the cache has it, then loads it.
// `name` labels the files in the cache; `extra_flags` are added to the compiler's (and the key).
// Throws std::runtime_error with the compiler's output.
loaded_library compile_and_load(const std::string& source, const std::string& name,
                                const std::string& extra_flags = "");

} // namespace rotgen

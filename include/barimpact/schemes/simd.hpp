// The SIMD path of the batch kernels (PaperBatch), chosen at run time by
// what the processor has: the widest, unless BARIMPACT_SIMD names one.
// Every path gives the same bits (tests/unit/paper_batch_test.cpp compares
// them); they differ only in speed.
//   scalar  one lane at a time (no vector instructions)
//   sse2    two lanes per instruction (every x86-64 processor)
//   avx2    four lanes per instruction
#pragma once

#include <optional>
#include <string_view>
#include <vector>

namespace barimpact {

enum class SimdPath { scalar, sse2, avx2 };

[[nodiscard]] std::string_view to_string(SimdPath path);

/// The paths this build has and this processor runs, narrowest first.
[[nodiscard]] std::vector<SimdPath> supported_simd_paths();

/// The path the batches take: BARIMPACT_SIMD's if set, else the widest
/// supported. Throws InputError naming BARIMPACT_SIMD when it names no
/// path, or one this processor cannot run.
[[nodiscard]] SimdPath simd_path();

/// Forces a path (tests, benchmarks); nullopt returns to simd_path()'s choice.
/// Throws InputError if this processor cannot run it.
void force_simd_path(std::optional<SimdPath> path);

}  // namespace barimpact

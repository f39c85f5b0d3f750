#pragma once
// Discrete distribution sampled in O(1) with Walker's alias method, built with Vose's
// numerically stable construction (Vose 1991, "A Linear Algorithm for Generating Random
// Numbers with a Given Distribution", IEEE TSE 17(9)). The reference picks lights with it.

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

namespace giq::reference {

class AliasTable {
 public:
  AliasTable() = default;
  // Weights must be finite and non-negative with a positive sum; throws std::invalid_argument
  // otherwise.
  explicit AliasTable(std::span<const double> weights);

  size_t size() const { return pmf_.size(); }
  bool empty() const { return pmf_.empty(); }
  float pmf(size_t i) const { return pmf_[i]; }

  struct Pick {
    uint32_t index;
    float pmf;
  };
  // u_bin selects a bin, u_alias the bin's own entry or its alias. Two numbers, because the
  // fraction left in one float after selecting among a million bins has only a few bits.
  Pick sample(float u_bin, float u_alias) const {
    const uint32_t bin = std::min(uint32_t(double(u_bin) * double(bins_.size())), uint32_t(bins_.size() - 1));
    const uint32_t i = u_alias < bins_[bin].threshold ? bin : bins_[bin].alias;
    return {i, pmf_[i]};
  }

 private:
  struct Bin {
    float threshold;
    uint32_t alias;
  };
  std::vector<float> pmf_;
  std::vector<Bin> bins_;
};

}  // namespace giq::reference

#include "scanloc/likelihood/laser_signature.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace scanloc {
namespace {

// Scales a median absolute deviation to the σ of a normal distribution.
constexpr double kMadToSigma = 1.4826;

// The median of sorted values (not empty): the middle one, or the mean of the two middle ones.
double MedianOfSorted(const std::vector<double>& sorted) {
  const std::size_t mid = sorted.size() / 2;
  const double upper = sorted[mid];
  if (sorted.size() % 2 == 1) return upper;
  return 0.5 * (upper + sorted[mid - 1]);
}

// The median of |v − centre| over sorted values (not empty), without sorting the deviations: they
// grow from the values nearest the centre outwards on either side, so the smallest come from a
// merge of the two sides, and only the first half of them is walked.
double MedianDeviationOfSorted(const std::vector<double>& sorted, double centre) {
  const std::size_t n = sorted.size(), mid = n / 2;
  std::size_t right = static_cast<std::size_t>(
      std::lower_bound(sorted.begin(), sorted.end(), centre) - sorted.begin());
  std::size_t left = right;  // the next value on the left is sorted[left − 1]
  double previous = 0.0, current = 0.0;
  for (std::size_t taken = 0; taken <= mid; ++taken) {
    previous = current;
    const bool from_left = right == n || (left > 0 && std::abs(sorted[left - 1] - centre) <=
                                                          std::abs(sorted[right] - centre));
    current = from_left ? std::abs(sorted[--left] - centre) : std::abs(sorted[right++] - centre);
  }
  if (n % 2 == 1) return current;
  return 0.5 * (current + previous);
}

std::vector<double> Normalised(const std::vector<int>& histogram) {
  double total = 0.0;
  for (const int count : histogram) total += count;
  std::vector<double> normalised(histogram.size(), 0.0);
  if (total <= 0.0) return normalised;
  for (std::size_t k = 0; k < histogram.size(); ++k) normalised[k] = histogram[k] / total;
  return normalised;
}

}  // namespace

void LaserSignatureOptions::Validate() const {
  auto require = [](bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(std::string("LaserSignatureOptions: ") + what);
  };
  require(window >= 0 && window <= 100000, "window must be in [0, 100000]");
  require(min_samples >= 1, "min_samples must be >= 1");
  require(min_samples <= window || window == 0, "min_samples must not exceed window");
  require(std::isfinite(spread_factor) && spread_factor > 0.0, "spread_factor must be positive");
}

LaserSignature::LaserSignature(LaserSignatureOptions options) : options_(options) {
  options_.Validate();
}

void LaserSignature::Add(const LikelihoodTestResult& confirmed) {
  if (options_.window == 0 || confirmed.match_pairs == 0) return;
  expect_values_m_.Push(confirmed.expect_value_m);
  histograms_.push_back(Normalised(confirmed.histogram));
  if (expect_values_m_.size() > static_cast<std::size_t>(options_.window)) {
    expect_values_m_.PopOldest();
    histograms_.pop_front();
  }
}

bool LaserSignature::learned() const {
  return options_.window > 0 &&
         expect_values_m_.size() >= static_cast<std::size_t>(options_.min_samples);
}

double LaserSignature::ExpectValueBound(double prior_m) const {
  if (!learned()) return prior_m;
  const std::vector<double>& values = expect_values_m_.sorted();
  const double median = MedianOfSorted(values);
  const double sigma = kMadToSigma * MedianDeviationOfSorted(values, median);
  return std::max(prior_m, median + options_.spread_factor * sigma);
}

std::vector<double> LaserSignature::MeanHistogram() const {
  if (histograms_.empty()) return {};
  std::vector<double> mean(histograms_.front().size(), 0.0);
  for (const auto& h : histograms_)
    for (std::size_t k = 0; k < mean.size() && k < h.size(); ++k) mean[k] += h[k];
  for (double& m : mean) m /= static_cast<double>(histograms_.size());
  return mean;
}

double LaserSignature::HistogramDistance(const LikelihoodTestResult& test) const {
  const std::vector<double> mean = MeanHistogram();
  if (mean.empty() || test.match_pairs == 0) return 0.0;
  const std::vector<double> h = Normalised(test.histogram);
  double distance = 0.0;
  for (std::size_t k = 0; k < mean.size() && k < h.size(); ++k)
    distance += std::abs(h[k] - mean[k]);
  return distance;
}

}  // namespace scanloc

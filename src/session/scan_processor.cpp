#include "scanloc/session/scan_processor.hpp"

#include <stdexcept>

namespace scanloc {

IterationRecord BeginRecord(const Iteration& iteration, std::size_t index) {
  iteration.scan.CheckConsistent();
  IterationRecord record;
  record.index = index;
  record.timestamp_s = iteration.timestamp_s;
  record.origin = iteration.origin;
  return record;
}

IterationRecord ScanProcessor::Replay(const Iteration&, const RecordedIteration&) {
  throw std::logic_error("this processor cannot resume a run from its records");
}

}  // namespace scanloc

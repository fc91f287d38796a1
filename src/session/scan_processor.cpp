#include "scanloc/session/scan_processor.hpp"

namespace scanloc {

IterationRecord BeginRecord(const Iteration& iteration, std::size_t index) {
  iteration.scan.CheckConsistent();
  IterationRecord record;
  record.index = index;
  record.timestamp_s = iteration.timestamp_s;
  record.origin = iteration.origin;
  return record;
}

}  // namespace scanloc

#include "taebp/scenario/ssm_args.h"

#include <sstream>

namespace taebp {

std::vector<std::string> SsmSumoArgs(const SsmConfig& ssm, const std::string& file) {
  std::string measures;
  std::ostringstream thresholds;
  thresholds.precision(17);
  for (const std::string& m : ssm.measures) {
    measures += (measures.empty() ? "" : " ") + m;
    const double t = m == "TTC" ? ssm.thresholds.ttc
                     : m == "DRAC" ? ssm.thresholds.drac
                                   : ssm.thresholds.pet;
    if (thresholds.tellp() > 0) thresholds << ' ';
    thresholds << t;
  }
  return {"--device.ssm.probability", "1",       "--device.ssm.deterministic", "true",
          "--device.ssm.measures",    measures,  "--device.ssm.thresholds",    thresholds.str(),
          "--device.ssm.file",        file};
}

}  // namespace taebp

#include "taebp/scenario/ssm_args.h"

#include "taebp/base/number_text.h"

namespace taebp {

std::vector<std::string> SsmSumoArgs(const SsmConfig& ssm, const std::string& file) {
  std::string measures, thresholds;
  for (const std::string& m : ssm.measures) {
    measures += (measures.empty() ? "" : " ") + m;
    const double t = m == "TTC" ? ssm.thresholds.ttc
                     : m == "DRAC" ? ssm.thresholds.drac
                                   : ssm.thresholds.pet;
    thresholds += (thresholds.empty() ? "" : " ") + NumberText(t, 17);
  }
  return {"--device.ssm.probability", "1",       "--device.ssm.deterministic", "true",
          "--device.ssm.measures",    measures,  "--device.ssm.thresholds",    thresholds,
          "--device.ssm.file",        file};
}

std::string SsmAbortHint() {
  return "SUMO 1.15's SSM device (scenario.outputs.ssm) aborts when two vehicles that collided "
         "leave their conflict area in the same step (MSDevice_SSM.cpp:1870, assertion in "
         "updatePassedEncounter; docs/ssm.md): run this seed without scenario.outputs.ssm";
}

}  // namespace taebp

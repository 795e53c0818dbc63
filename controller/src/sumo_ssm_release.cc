// SUMO 1.15's SSM device in Debian's build: two assertions turned into what
// upstream's release builds do (sumo_adapter.h SsmReleaseBehaviour,
// docs/ssm.md "No run lost to SUMO's assertion").
//
// MSDevice_SSM::updatePassedEncounter (MSDevice_SSM.cpp:1864-1870) ends a
// crossing encounter whose two vehicles have both left their conflict area:
//
//     eInfo.type = ENCOUNTER_TYPE_BOTH_LEFT_CONFLICT_AREA;
//     // It should not occur that both leave the conflict at the same step
//     assert(lastPotentialConflictType == FOE_LEFT || == EGO_LEFT
//            || == BOTH_ENTERED || == BOTH_LEFT);
//
// Two vehicles the device saw inside the conflict area at once (its
// "detected collision": a collision, or two vehicles passing close) can leave
// it in the same step; Debian builds SUMO with assertions, so the process
// aborts. Built with NDEBUG, as upstream's releases are, the assertion is
// gone and the encounter goes on classified as both left. In Debian 12's
// libsumocpp (sumo 1.15.0+dfsg-1+deb12u1) the check compiles to
//
//     sub $0xe,%r13d; movl $0x11,0x8(%rbx); cmp $0x3,%r13d; jbe <go on>
//     <the call of __assert_fail for line 0x74e>
//
// and the one change is that `jbe` (taken when the last type is one of the
// four allowed) becomes `jmp`: the type is set to both-left and the function
// goes on, as without the assertion.
//
// MSDevice_SSM::determinePET (MSDevice_SSM.cpp:1163-1172), for an encounter
// both have left, asserts that its previous type was one of the crossing or
// conflict-area types (10-16) unless it was already both-left (17). A merge
// that collided where SUMO finds no crossing point between the two internal
// lanes ("bad internal lane geometry") reaches it with another type (seen with
// merges as games: grid_two_way, No Trust, seed 1, t = 520.7 s at D3). Without
// the assertion the function goes on to the PET computation. It compiles to
//
//     cmp $0x11,%edx; je <both left>; sub $0xa,%edx; cmp $0x6,%edx;
//     jbe <PET>; <the call of __assert_fail for line 0x494>
//
// and the one change is that `jbe` rel8 (76) becomes `jmp` rel8 (eb): the same
// target. Nothing is changed unless the bytes around each site are exactly
// those of that build.
#include "taebp/controller/sumo_adapter.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <vector>

#include <dlfcn.h>
#include <sys/mman.h>
#include <unistd.h>

namespace taebp::sumo {
namespace {

// One assertion's check: where it is, the bytes there in Debian 12's build,
// and the jump's replacement at original + jump.
struct Site {
  const char* function;
  std::size_t at;  // from the function's start
  std::vector<unsigned char> original;
  std::size_t jump;
  std::vector<unsigned char> released;
};

// MSDevice_SSM.cpp:1870, from updatePassedEncounter's start + 0x330: sub, movl
// (type = both left), cmp, jbe rel32, lea, mov $0x74e,%edx. jbe rel32
// (0f 86 r) -> jmp rel32 + 1 (e9 r+1), nop: the same target.
// MSDevice_SSM.cpp:1172, from determinePET's start + 0x2e: cmp $0x11,%edx,
// je, sub $0xa,%edx, cmp $0x6,%edx, jbe rel8, lea, mov $0x494,%edx.
const Site kSites[] = {
    {"_ZN12MSDevice_SSM21updatePassedEncounterEPNS_9EncounterEPNS_7FoeInfoERNS_"
     "21EncounterApproachInfoE",
     0x330,
     {0x41, 0x83, 0xed, 0x0e, 0xc7, 0x43, 0x08, 0x11, 0x00, 0x00, 0x00, 0x41,
      0x83, 0xfd, 0x03, 0x0f, 0x86, 0x8c, 0xfe, 0xff, 0xff, 0x48, 0x8d, 0x0d,
      0xfc, 0x95, 0x5a, 0x00, 0xba, 0x4e, 0x07, 0x00, 0x00},
     15,
     {0xe9, 0x8d, 0xfe, 0xff, 0xff, 0x90}},
    {"_ZNK12MSDevice_SSM12determinePETERNS_21EncounterApproachInfoE",
     0x2e,
     {0x83, 0xfa, 0x11, 0x74, 0x2d, 0x83, 0xea, 0x0a, 0x83, 0xfa, 0x06, 0x76, 0x45,
      0x48, 0x8d, 0x0d, 0xc6, 0xae, 0x5a, 0x00, 0xba, 0x94, 0x04, 0x00, 0x00},
     11,
     {0xeb}},
};

// "applied" (also when an earlier call of this process did it) or why not.
std::string Release(const Site& site) {
  auto* f = static_cast<unsigned char*>(::dlsym(RTLD_DEFAULT, site.function));
  if (!f) return std::string("not applied: this SUMO library has no ") + site.function;
  unsigned char* code = f + site.at;
  std::vector<unsigned char> expected = site.original;
  std::copy(site.released.begin(), site.released.end(), expected.begin() + site.jump);
  if (std::memcmp(code, expected.data(), expected.size()) == 0) return "applied";
  if (std::memcmp(code, site.original.data(), site.original.size()) != 0)
    return "not applied: this SUMO library is not Debian 12's sumo 1.15.0 build (its SSM "
           "device may abort as described in docs/ssm.md)";
  const long page = ::sysconf(_SC_PAGESIZE);
  unsigned char* jump = code + site.jump;
  auto* first = reinterpret_cast<unsigned char*>(reinterpret_cast<std::uintptr_t>(jump) &
                                                 ~static_cast<std::uintptr_t>(page - 1));
  const std::size_t length = static_cast<std::size_t>(jump + site.released.size() - first);
  if (::mprotect(first, length, PROT_READ | PROT_WRITE | PROT_EXEC) != 0)
    return "not applied: the SUMO library's code cannot be changed in this process";
  std::memcpy(jump, site.released.data(), site.released.size());
  ::mprotect(first, length, PROT_READ | PROT_EXEC);
  return "applied";
}

std::string g_state;  // what SsmReleaseBehaviour did (once per process)

}  // namespace

std::string SsmReleaseBehaviour() {
  if (!g_state.empty()) return g_state;
  for (const Site& site : kSites) {
    const std::string state = Release(site);
    if (state != "applied") return g_state = state;
  }
  return g_state = "applied";
}

}  // namespace taebp::sumo

// SUMO 1.15's SSM device in Debian's build: one assertion turned into what
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
// goes on, as without the assertion. Nothing is changed unless the bytes
// around it are exactly those of that build.
#include "taebp/controller/sumo_adapter.h"

#include <cstdint>
#include <cstring>

#include <dlfcn.h>
#include <sys/mman.h>
#include <unistd.h>

namespace taebp::sumo {
namespace {

constexpr const char* kFunction =
    "_ZN12MSDevice_SSM21updatePassedEncounterEPNS_9EncounterEPNS_7FoeInfoERNS_"
    "21EncounterApproachInfoE";
// The check and the start of the failure branch, from the function's start
// + 0x330: sub, movl (type = both left), cmp, jbe rel32, lea, mov $0x74e,%edx.
constexpr std::size_t kAt = 0x330;
constexpr unsigned char kOriginal[] = {
    0x41, 0x83, 0xed, 0x0e, 0xc7, 0x43, 0x08, 0x11, 0x00, 0x00, 0x00, 0x41,
    0x83, 0xfd, 0x03, 0x0f, 0x86, 0x8c, 0xfe, 0xff, 0xff, 0x48, 0x8d, 0x0d,
    0xfc, 0x95, 0x5a, 0x00, 0xba, 0x4e, 0x07, 0x00, 0x00};
constexpr std::size_t kJump = 15;  // the jbe's offset in kOriginal
// jbe rel32 (0f 86 r) -> jmp rel32 + 1 (e9 r+1), nop: the same target.
constexpr unsigned char kReleased[6] = {0xe9, 0x8d, 0xfe, 0xff, 0xff, 0x90};

std::string g_state;  // what SsmReleaseBehaviour did (once per process)

}  // namespace

std::string SsmReleaseBehaviour() {
  if (!g_state.empty()) return g_state;
  auto* f = static_cast<unsigned char*>(::dlsym(RTLD_DEFAULT, kFunction));
  if (!f) return g_state = "not applied: this SUMO library has no MSDevice_SSM::updatePassedEncounter";
  unsigned char* code = f + kAt;
  unsigned char expected[sizeof kOriginal];
  std::memcpy(expected, kOriginal, sizeof kOriginal);
  std::memcpy(expected + kJump, kReleased, sizeof kReleased);
  if (std::memcmp(code, expected, sizeof expected) == 0) return g_state = "applied";
  if (std::memcmp(code, kOriginal, sizeof kOriginal) != 0)
    return g_state =
               "not applied: this SUMO library is not Debian 12's sumo 1.15.0 build (its SSM "
               "device may abort as described in docs/ssm.md)";
  const long page = ::sysconf(_SC_PAGESIZE);
  unsigned char* jump = code + kJump;
  auto* first = reinterpret_cast<unsigned char*>(reinterpret_cast<std::uintptr_t>(jump) &
                                                 ~static_cast<std::uintptr_t>(page - 1));
  const std::size_t length = static_cast<std::size_t>(jump + sizeof kReleased - first);
  if (::mprotect(first, length, PROT_READ | PROT_WRITE | PROT_EXEC) != 0)
    return g_state = "not applied: the SUMO library's code cannot be changed in this process";
  std::memcpy(jump, kReleased, sizeof kReleased);
  ::mprotect(first, length, PROT_READ | PROT_EXEC);
  return g_state = "applied";
}

}  // namespace taebp::sumo
